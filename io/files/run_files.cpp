#include "io/files/run_files.hpp"

#include <limits.h>
#include <sys/stat.h>
#include <unistd.h>

#include <algorithm>
#include <cerrno>
#include <cstring>
#include <optional>
#include <system_error>

#include "io/files/output_file.hpp"
#include "io/input_error.hpp"

namespace irloc::io {
namespace {

namespace fs = std::filesystem;

struct Identity {
  dev_t device = 0;
  ino_t inode = 0;
  bool operator==(const Identity&) const = default;
};

std::optional<Identity> identity_of(const fs::path& path) {
  struct stat status {};
  if (::stat(path.c_str(), &status) != 0) return std::nullopt;
  return Identity{status.st_dev, status.st_ino};
}

// The absolute path with every link and `..` of its existing part resolved.
fs::path resolved(const fs::path& path) {
  std::error_code error;
  const fs::path canonical = fs::weakly_canonical(fs::absolute(path, error), error);
  return error ? fs::absolute(path).lexically_normal() : canonical;
}

bool is_within(const fs::path& inner, const fs::path& outer) {
  auto a = inner.begin();
  for (auto b = outer.begin(); b != outer.end(); ++b, ++a) {
    if (b->empty()) continue;  // a trailing separator
    if (a == inner.end() || *a != *b) return false;
  }
  return true;
}

[[noreturn]] void refuse(const std::string& flag, const fs::path& path, const std::string& problem) {
  throw InputError(flag + " " + path.string() + ": " + problem);
}

// The nearest existing ancestor of a path that does not exist must be a folder we can write in.
void check_creatable(const std::string& flag, const fs::path& path) {
  for (fs::path ancestor = folder_of(fs::absolute(path)); ; ancestor = ancestor.parent_path()) {
    struct stat status {};
    if (::stat(ancestor.c_str(), &status) == 0) {
      if (!S_ISDIR(status.st_mode)) refuse(flag, path, "lies under " + ancestor.string() + ", which is no folder");
      if (::access(ancestor.c_str(), W_OK) != 0) {
        refuse(flag, path, "cannot create it in " + ancestor.string() + ": " + std::strerror(errno));
      }
      return;
    }
    if (errno != ENOENT && errno != ENOTDIR) refuse(flag, path, std::string("cannot reach it: ") + std::strerror(errno));
    if (ancestor == ancestor.root_path()) return;
  }
}

void check_name_length(const std::string& flag, const fs::path& path) {
  const std::string name = path.filename().string();
  if (name.empty() || name == "." || name == "..") refuse(flag, path, "names a folder, expected a file name");
  long name_max = ::pathconf(folder_of(path).c_str(), _PC_NAME_MAX);
  if (name_max <= 0) name_max = NAME_MAX;
  if (name.size() + kTemporaryNameExtra > static_cast<std::size_t>(name_max)) {
    refuse(flag, path, "the file name is too long: its temporary file (.NAME.XXXXXX) needs " +
                           std::to_string(name.size() + kTemporaryNameExtra) + " characters, more than the " +
                           std::to_string(name_max) + " its folder allows");
  }
}

// A file that will be replaced whole or created.
void check_file(const std::string& flag, const fs::path& path, bool folder_is_created) {
  check_name_length(flag, path);
  if (folder_is_created) return;
  struct stat status {};
  if (::lstat(path.c_str(), &status) != 0) {
    if (errno != ENOENT && errno != ENOTDIR) refuse(flag, path, std::string("cannot reach it: ") + std::strerror(errno));
    const fs::path folder = folder_of(path);
    struct stat folder_status {};
    if (::stat(folder.c_str(), &folder_status) != 0) {
      if (errno == ENOENT) refuse(flag, path, "its folder " + folder.string() + " does not exist");
      if (errno == ENOTDIR) check_creatable(flag, folder);  // names the file it lies under
      refuse(flag, path, "cannot reach its folder " + folder.string() + ": " + std::strerror(errno));
    }
    if (!S_ISDIR(folder_status.st_mode)) refuse(flag, path, "lies under " + folder.string() + ", which is no folder");
  } else if (S_ISLNK(status.st_mode)) {
    refuse(flag, path, "is a symbolic link: refusing to replace it or write through it (give the file it points to)");
  } else if (S_ISDIR(status.st_mode)) {
    refuse(flag, path, "is a folder, expected a file");
  } else if (!S_ISREG(status.st_mode)) {
    refuse(flag, path, "is a special file (FIFO, device or socket): refusing to replace it");
  }
  const fs::path folder = folder_of(path);
  if (::access(folder.c_str(), W_OK) != 0) {
    refuse(flag, path, "cannot write in its folder " + folder.string() + ": " + std::strerror(errno));
  }
}

void check_folder(const std::string& flag, const fs::path& path, bool must_be_empty) {
  struct stat status {};
  if (::stat(path.c_str(), &status) != 0) {
    if (errno != ENOENT && errno != ENOTDIR) refuse(flag, path, std::string("cannot reach it: ") + std::strerror(errno));
    check_creatable(flag, path);
    return;
  }
  if (!S_ISDIR(status.st_mode)) refuse(flag, path, "is no folder");
  if (::access(path.c_str(), W_OK) != 0) refuse(flag, path, std::string("cannot write in it: ") + std::strerror(errno));
  std::error_code error;
  if (must_be_empty && fs::directory_iterator(path, error) != fs::directory_iterator()) {
    refuse(flag, path, "the folder is not empty: give a new or empty folder (nothing is overwritten)");
  }
}

}  // namespace

void RunFiles::input(const fs::path& path) { inputs_.push_back(path); }

void RunFiles::inputs(const std::vector<fs::path>& paths) { inputs_.insert(inputs_.end(), paths.begin(), paths.end()); }

void RunFiles::output_file(const std::string& flag, const fs::path& path) { files_.push_back({flag, path, false}); }

void RunFiles::new_folder(const std::string& flag, const fs::path& path) { folders_.push_back({flag, path, true}); }

void RunFiles::replaced_folder(const std::string& flag, const fs::path& path) { replaced_folders_.push_back({flag, path, false}); }

void RunFiles::output_folder(const std::string& flag, const fs::path& path, const std::vector<std::string>& names) {
  folders_.push_back({flag, path, false});
  std::error_code error;
  const bool created = !fs::exists(path, error);
  for (const std::string& name : names) files_.push_back({flag, path / name, created});
}

void RunFiles::check() const {
  for (const Folder& folder : folders_) check_folder(folder.flag, folder.path, folder.must_be_empty);
  // What an output is to the run's other files first: that says more than "its folder does not
  // exist" about a file in a folder another output creates.
  for (const Output& file : files_) {
    const fs::path where = resolved(file.path);
    const std::optional<Identity> identity = identity_of(file.path);
    for (const fs::path& input : inputs_) {
      if (where == resolved(input) || (identity && identity == identity_of(input))) {
        refuse(file.flag, file.path, "is the input file " + input.string() + ": refusing to overwrite it");
      }
    }
    for (const Output& other : files_) {
      if (&other == &file) break;  // each pair once, named in command-line order
      if (where == resolved(other.path) || (identity && identity == identity_of(other.path))) {
        refuse(file.flag, file.path, "is also the output of " + other.flag + " " + other.path.string() +
                                         ": give each output a file of its own");
      }
    }
    for (const Folder& folder : folders_) {
      if (folder.must_be_empty && is_within(where, resolved(folder.path))) {
        refuse(file.flag, file.path, "lies in the new folder of " + folder.flag + " " + folder.path.string() +
                                         ": give each output a place of its own");
      }
    }
  }
  for (const Folder& folder : folders_) {
    for (const Folder& other : folders_) {
      if (&other == &folder) break;
      const fs::path a = resolved(folder.path), b = resolved(other.path);
      if ((folder.must_be_empty || other.must_be_empty) && (is_within(a, b) || is_within(b, a))) {
        refuse(folder.flag, folder.path, "overlaps the folder of " + other.flag + " " + other.path.string() +
                                             ": give each output a place of its own");
      }
    }
  }
  for (const Folder& folder : replaced_folders_) {
    struct stat status {};
    if (::lstat(folder.path.c_str(), &status) == 0 && !S_ISDIR(status.st_mode)) {
      refuse(folder.flag, folder.path, S_ISLNK(status.st_mode) ? "is a symbolic link: refusing to replace what it points to"
                                                               : "is no folder: refusing to replace it");
    }
    for (const fs::path& input : inputs_) {
      if (is_within(resolved(input), resolved(folder.path))) {
        refuse(folder.flag, folder.path, "holds the input file " + input.string() + ": refusing to replace the folder");
      }
    }
  }
  for (const Output& file : files_) check_file(file.flag, file.path, file.in_new_folder);
  for (const Output& file : files_) {
    if (!file.in_new_folder) remove_stale_temporaries(file.path);
  }
}

}  // namespace irloc::io
