#pragma once
// Writing output files without harming what is already on disk.

#include <sys/types.h>

#include <cstddef>
#include <filesystem>
#include <string>

#include "io/files/input_file.hpp"

namespace irloc::io {

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

// The one temporary-file helper. Replaces `path` with `text` atomically: writes a new temporary
// file `.NAME.XXXXXX` (unique, O_EXCL: never through a link) in the same folder with `mode`,
// fsyncs it, renames it over `path` and fsyncs the folder, so that a power cut leaves the old file
// or the new one, never a torn one. Throws InputError "PATH: cannot write WHAT (STEP): REASON"
// when a step fails (the disk full); the temporary file is then removed and the old file stays.
// Refuses to replace anything but a regular file (io/files/run_files.hpp checks that at start).
void replace_file_atomically(const std::filesystem::path& path, const std::string& text, mode_t mode = 0644,
                             const char* what = "the file");

// The folder `path` names a file in: its parent, or "." for a bare name.
std::filesystem::path folder_of(const std::filesystem::path& path);

// The characters a temporary file's name adds to the target's: `.` before it, `.XXXXXX` after it.
inline constexpr std::size_t kTemporaryNameExtra = 8;

// Removes the temporary files of `path` (`.NAME.XXXXXX`, regular files) that a killed run left in
// its folder.
void remove_stale_temporaries(const std::filesystem::path& path);

}  // namespace irloc::io
