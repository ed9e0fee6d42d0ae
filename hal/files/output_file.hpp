#pragma once
// Writing output files without harming what is already on disk.

#include <sys/types.h>

#include <cstddef>
#include <filesystem>
#include <string>
#include <vector>

#include "hal/files/input_file.hpp"

namespace irloc::hal {

// A folder for a new set of files (a recorded dataset): created when absent, refused when it
// already holds anything. Files are created in it with O_EXCL | O_NOFOLLOW, so that a file or a
// symbolic link planted in it is never overwritten or written through.
class NewFilesFolder {
 public:
  explicit NewFilesFolder(const std::filesystem::path& dir);

  // Creates `name` (a plain file name) for writing; throws InputError when it exists.
  UniqueFd create(const char* name) const;
  const std::filesystem::path& path() const { return dir_; }

 private:
  std::filesystem::path dir_;
  UniqueFd fd_;
};

// Writes all `size` bytes, retrying short writes; throws InputError "NAME: cannot write: ...".
void write_all(int fd, const void* data, std::size_t size, const std::string& name);

// Replaces `path` with `text` atomically: writes a temporary file in the same folder with `mode`,
// fsyncs it, renames it over `path` and fsyncs the folder, so that a power cut leaves the old file
// or the new one, never a torn one. Throws InputError "PATH: cannot write WHAT (STEP): REASON"
// when a step fails (the old file then stays).
void replace_file_atomically(const std::filesystem::path& path, const std::string& text, mode_t mode, const char* what);

// Throws InputError when `output` (given by `option`) names an existing file that is one of
// `inputs` (the same file, through any path or link).
void refuse_overwriting_inputs(const std::filesystem::path& output, const std::string& option,
                               const std::vector<std::filesystem::path>& inputs);

}  // namespace irloc::hal
