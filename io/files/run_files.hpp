#pragma once
// The one output-file policy: every file a command writes is named here, with the files it reads,
// and checked together before any work starts (docs/formats.md, "Output files").
//
// An output file may not be
//   - an input of the same run (the same device and inode, or the same resolved path),
//   - another output of the same run (the same resolved path or file), or lie in a folder that
//     must be new (--record, --annotate),
//   - a folder, a FIFO, a device or a socket, or a symbolic link (which would be replaced, or
//     written through),
//   - under something that is no folder, in a folder that does not exist or cannot be written,
//   - a name too long for its temporary file (`.NAME.XXXXXX`, NAME_MAX of its folder);
// a folder the run replaces whole may not be a symbolic link or hold an input.
// A refusal is one io::InputError "FLAG PATH: PROBLEM"; nothing has been written then.

#include <filesystem>
#include <string>
#include <vector>

namespace irloc::io {

class RunFiles {
 public:
  // A file the run reads.
  void input(const std::filesystem::path& path);
  void inputs(const std::vector<std::filesystem::path>& paths);
  // A file the run writes (replaced whole, or created), given by the command-line flag `flag`.
  void output_file(const std::string& flag, const std::filesystem::path& path);
  // A folder the run fills with new files (a dataset, pictures): absent, or an empty folder.
  void new_folder(const std::string& flag, const std::filesystem::path& path);
  // A folder the run removes, when there, and writes anew (irloc-sim run's DIR/dataset): absent or
  // a folder (no symbolic link), holding no input of the run.
  void replaced_folder(const std::string& flag, const std::filesystem::path& path);
  // A folder (created when absent) in which the run replaces the files `names`.
  void output_folder(const std::string& flag, const std::filesystem::path& path, const std::vector<std::string>& names);

  // Checks every output against the policy above, then removes the temporary files a killed
  // earlier run left beside them (`.NAME.XXXXXX`). Throws io::InputError for the first refusal.
  void check() const;

 private:
  struct Output {
    std::string flag;
    std::filesystem::path path;
    bool in_new_folder = false;  // its folder is created by the run (checked as a folder)
  };
  struct Folder {
    std::string flag;
    std::filesystem::path path;
    bool must_be_empty = false;
  };
  std::vector<std::filesystem::path> inputs_;
  std::vector<Output> files_;
  std::vector<Folder> folders_;
  std::vector<Folder> replaced_folders_;
};

}  // namespace irloc::io
