#include "io/files/output_file.hpp"

#include <fcntl.h>
#include <sys/stat.h>
#include <unistd.h>

#include <algorithm>
#include <cctype>
#include <cerrno>
#include <cstdlib>
#include <cstring>
#include <system_error>

#include "io/input_error.hpp"

namespace irloc::io {
NewFilesFolder::NewFilesFolder(const std::filesystem::path& dir) : dir_(dir) {
  std::error_code error;
  std::filesystem::create_directories(dir_, error);
  if (error) throw InputError(dir_.string() + ": cannot create the folder: " + error.message());
  fd_ = UniqueFd(::open(dir_.c_str(), O_RDONLY | O_DIRECTORY | O_CLOEXEC));
  if (fd_.get() < 0) throw InputError(dir_.string() + ": cannot open the folder: " + std::strerror(errno));
  if (std::filesystem::directory_iterator(dir_, error) != std::filesystem::directory_iterator()) {
    throw InputError(dir_.string() + ": the folder is not empty: give a new or empty folder (nothing is overwritten)");
  }
  if (error) throw InputError(dir_.string() + ": cannot list the folder: " + error.message());
}

UniqueFd NewFilesFolder::create(const char* name) const {
  UniqueFd file(::openat(fd_.get(), name, O_WRONLY | O_CREAT | O_EXCL | O_NOFOLLOW | O_CLOEXEC, 0644));
  if (file.get() < 0) throw InputError((dir_ / name).string() + ": cannot create: " + std::strerror(errno));
  return file;
}

void write_all(int fd, const void* data, std::size_t size, const std::string& name) {
  const char* bytes = static_cast<const char*>(data);
  while (size > 0) {
    const ssize_t written = ::write(fd, bytes, size);
    if (written < 0 && errno == EINTR) continue;
    if (written <= 0) throw InputError(name + ": cannot write: " + std::strerror(written < 0 ? errno : ENOSPC));
    bytes += written;
    size -= static_cast<std::size_t>(written);
  }
}

std::filesystem::path folder_of(const std::filesystem::path& path) {
  return path.has_parent_path() ? path.parent_path() : std::filesystem::path(".");
}

namespace {

// `.NAME.` + the six characters mkstemp puts in place of XXXXXX.
bool is_temporary_of(const std::string& candidate, const std::string& name) {
  if (candidate.size() != name.size() + kTemporaryNameExtra || candidate[0] != '.' ||
      candidate.compare(1, name.size(), name) != 0 || candidate[name.size() + 1] != '.') {
    return false;
  }
  return std::all_of(candidate.end() - 6, candidate.end(), [](char c) { return std::isalnum(static_cast<unsigned char>(c)) != 0; });
}

}  // namespace

void replace_file_atomically(const std::filesystem::path& path, const std::string& text, mode_t mode, const char* what) {
  const auto fail_with = [&](const char* step, int error) {
    throw InputError(path.string() + ": cannot write " + what + " (" + step + "): " + std::strerror(error));
  };
  struct stat existing {};
  if (::lstat(path.c_str(), &existing) == 0 && !S_ISREG(existing.st_mode)) {
    throw InputError(path.string() + ": cannot write " + what + ": is no regular file: refusing to replace it");
  }
  const std::filesystem::path folder = folder_of(path);
  std::string name = path.filename().string();
  name.insert(0, 1, '.');
  name.append(".XXXXXX");
  std::string temporary = (folder / name).string();
  const int file = ::mkostemp(temporary.data(), O_CLOEXEC);
  if (file < 0) fail_with("create a temporary file in its folder", errno);
  const auto fail_and_remove = [&](const char* step, int error) {
    ::close(file);
    ::unlink(temporary.c_str());
    fail_with(step, error);
  };
  std::size_t written = 0;
  while (written < text.size()) {
    const ssize_t n = ::write(file, text.data() + written, text.size() - written);
    if (n < 0 && errno == EINTR) continue;
    if (n <= 0) fail_and_remove("write", n < 0 ? errno : ENOSPC);
    written += static_cast<std::size_t>(n);
  }
  if (::fchmod(file, mode) != 0) fail_and_remove("chmod", errno);
  if (::fsync(file) != 0) fail_and_remove("fsync", errno);
  if (::close(file) != 0) {
    const int error = errno;
    ::unlink(temporary.c_str());
    fail_with("close", error);
  }
  if (::rename(temporary.c_str(), path.c_str()) != 0) {
    const int error = errno;
    ::unlink(temporary.c_str());
    fail_with("rename", error);
  }
  const UniqueFd directory(::open(folder.c_str(), O_RDONLY | O_DIRECTORY | O_CLOEXEC));
  if (directory.get() < 0) fail_with("open its folder", errno);
  if (::fsync(directory.get()) != 0) fail_with("fsync its folder", errno);
}

void remove_stale_temporaries(const std::filesystem::path& path) {
  const std::string name = path.filename().string();
  std::error_code error;
  for (const std::filesystem::directory_entry& entry : std::filesystem::directory_iterator(folder_of(path), error)) {
    if (is_temporary_of(entry.path().filename().string(), name) && entry.is_regular_file(error) &&
        !entry.is_symlink(error)) {
      std::filesystem::remove(entry.path(), error);
    }
  }
}

}  // namespace irloc::io
