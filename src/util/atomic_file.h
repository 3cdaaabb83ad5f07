// Write-then-rename, so a failed or interrupted write never leaves a partial
// output file under the user's name.
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
  // Renames the temporary onto the final name; throws FileError on failure.
  void commit();

 private:
  std::string final_, temp_;
  bool committed_ = false;
};

}  // namespace zs
