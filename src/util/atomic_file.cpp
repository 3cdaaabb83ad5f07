#include "util/atomic_file.h"

#include <cerrno>
#include <cstdio>
#include <cstring>
#include <filesystem>
#include <random>

#include <fcntl.h>
#include <unistd.h>

#include "util/file_error.h"

namespace zs {

namespace fs = std::filesystem;

AtomicFile::AtomicFile(std::string final_path) : final_(std::move(final_path)) {
  fs::path p(final_);
  std::random_device rd;
  std::string tag = ".zs-tmp-" + std::to_string(::getpid()) + "-" + std::to_string(rd() % 1000000);
  // Insert the tag before the extension: out.vtu -> out.zs-tmp-123-45.vtu
  fs::path tmp = p.parent_path() / (p.stem().string() + tag + p.extension().string());
  temp_ = tmp.string();
}

AtomicFile::~AtomicFile() {
  if (!committed_) {
    std::error_code ec;
    fs::remove(temp_, ec);
    // TetGen writes two files (.node/.ele) from one base name.
    fs::path t(temp_);
    for (const char* ext : {".node", ".ele"}) fs::remove(fs::path(t).replace_extension(ext), ec);
  }
}

void AtomicFile::check_writable() const {
  std::error_code ec;
  if (fs::is_directory(final_, ec)) throw FileError(final_, "cannot write: is a directory");
  const int fd = ::open(temp_.c_str(), O_WRONLY | O_CREAT | O_EXCL, 0644);
  if (fd < 0) throw FileError(final_, std::string("cannot write: ") + std::strerror(errno));
  ::close(fd);
  ::unlink(temp_.c_str());
}

void AtomicFile::commit() {
  if (std::rename(temp_.c_str(), final_.c_str()) != 0) {
    throw FileError(final_, std::string("cannot write: ") + std::strerror(errno));
  }
  committed_ = true;
}

}  // namespace zs
