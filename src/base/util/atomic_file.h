// Write-then-rename, so a failed or interrupted write never leaves a partial
// output file under the user's name. The temporary is registered
// (base/util/temp_registry.h) so that a fatal signal removes it too.
#pragma once

#include <string>

namespace zs {

class AtomicFile {
 public:
  // Picks a temporary name in the same directory as `final_path`.
  explicit AtomicFile(std::string final_path);
  ~AtomicFile();  // removes the temporary file unless commit() succeeded
  AtomicFile(const AtomicFile&) = delete;
  AtomicFile& operator=(const AtomicFile&) = delete;

  // Where the writer should write; keeps the final name's extension so that
  // libraries choosing a format by extension still work.
  const std::string& temp_path() const { return temp_; }
  const std::string& final_path() const { return final_; }
  // Creates and removes the temporary, so that an unwritable destination
  // (no such directory, no permission, a directory under the final name)
  // fails before the work that would fill it. Throws FileError.
  void check_writable() const;
  // A library's error message with the temporary's name (whole path, or
  // file name alone) replaced by the final one: the user never chose the
  // temporary's name, so messages name the output.
  std::string name_final(std::string message) const;
  // Renames the temporary onto the final name; throws FileError on failure.
  void commit();

 private:
  std::string final_, temp_;
  bool committed_ = false;
  int slots_[3] = {-1, -1, -1};  // temp_registry slots: the temporary, and TetGen's .node/.ele pair
};

}  // namespace zs
