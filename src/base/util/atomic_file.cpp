#include "base/util/atomic_file.h"

#include <cerrno>
#include <cstdio>
#include <cstring>
#include <filesystem>
#include <random>
#include <utility>

#include <fcntl.h>
#include <unistd.h>

#include "base/util/file_error.h"
#include "base/util/temp_registry.h"

namespace zs {

namespace fs = std::filesystem;

AtomicFile::AtomicFile(std::string final_path) : final_(std::move(final_path)) {
  fs::path p(final_);
  std::random_device rd;
  std::string tag = ".zs-tmp-" + std::to_string(::getpid()) + "-" + std::to_string(rd() % 1000000);
  // Insert the tag before the extension: out.vtu -> out.zs-tmp-123-45.vtu
  fs::path tmp = p.parent_path() / (p.stem().string() + tag + p.extension().string());
  temp_ = tmp.string();
  slots_[0] = register_temp_file(temp_);
  // TetGen writes <base>.node and <base>.ele from one base name.
  if (p.extension() == ".node" || p.extension() == ".ele") {
    slots_[1] = register_temp_file(fs::path(tmp).replace_extension(".node").string());
    slots_[2] = register_temp_file(fs::path(tmp).replace_extension(".ele").string());
  }
}

AtomicFile::~AtomicFile() {
  if (!committed_) {
    std::error_code ec;
    fs::remove(temp_, ec);
    // TetGen writes two files (.node/.ele) from one base name.
    fs::path t(temp_);
    for (const char* ext : {".node", ".ele"}) fs::remove(fs::path(t).replace_extension(ext), ec);
  }
  for (int s : slots_) unregister_temp_file(s);
}

void AtomicFile::check_writable() const {
  std::error_code ec;
  if (fs::is_directory(final_, ec)) throw FileError(final_, "cannot write: is a directory");
  const int fd = ::open(temp_.c_str(), O_WRONLY | O_CREAT | O_EXCL, 0644);
  if (fd < 0) throw FileError(final_, std::string("cannot write: ") + std::strerror(errno));
  ::close(fd);
  ::unlink(temp_.c_str());
}

std::string AtomicFile::name_final(std::string message) const {
  const auto replace_all = [&message](const std::string& from, const std::string& to) {
    for (size_t at = 0; !from.empty() && (at = message.find(from, at)) != std::string::npos; at += to.size())
      message.replace(at, from.size(), to);
  };
  replace_all(temp_, final_);
  replace_all(fs::path(temp_).filename().string(), fs::path(final_).filename().string());
  return message;
}

void AtomicFile::commit() {
  if (std::rename(temp_.c_str(), final_.c_str()) != 0) {
    throw FileError(final_, std::string("cannot write: ") + std::strerror(errno));
  }
  committed_ = true;
  for (int& s : slots_) unregister_temp_file(std::exchange(s, -1));
}

}  // namespace zs
