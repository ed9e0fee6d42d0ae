#include "hal/files/output_file.hpp"

#include <fcntl.h>
#include <sys/stat.h>
#include <unistd.h>

#include <cerrno>
#include <cstdlib>
#include <cstring>
#include <system_error>

#include "hal/input_error.hpp"

namespace irloc::hal {
namespace {

bool same_file(const struct stat& a, const struct stat& b) { return a.st_dev == b.st_dev && a.st_ino == b.st_ino; }

}  // namespace

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

void replace_file_atomically(const std::filesystem::path& path, const std::string& text, mode_t mode, const char* what) {
  const auto fail = [&](const char* step) {
    throw InputError(path.string() + ": cannot write " + what + " (" + step + "): " + std::strerror(errno));
  };
  const std::filesystem::path folder = path.has_parent_path() ? path.parent_path() : std::filesystem::path(".");
  std::string name = path.filename().string();
  name.insert(0, 1, '.');
  name.append(".XXXXXX");
  std::string temporary = (folder / name).string();
  const int file = ::mkstemp(temporary.data());
  if (file < 0) fail("create a temporary file in its folder");
  const auto fail_and_remove = [&](const char* step) {
    const int error = errno;
    ::close(file);
    ::unlink(temporary.c_str());
    errno = error;
    fail(step);
  };
  std::size_t written = 0;
  while (written < text.size()) {
    const ssize_t n = ::write(file, text.data() + written, text.size() - written);
    if (n < 0 && errno == EINTR) continue;
    if (n <= 0) fail_and_remove("write");
    written += static_cast<std::size_t>(n);
  }
  if (::fchmod(file, mode) != 0 || ::fsync(file) != 0) fail_and_remove("fsync");
  if (::close(file) != 0) {
    ::unlink(temporary.c_str());
    fail("close");
  }
  if (::rename(temporary.c_str(), path.c_str()) != 0) {
    const int error = errno;
    ::unlink(temporary.c_str());
    errno = error;
    fail("rename");
  }
  const int directory = ::open(folder.c_str(), O_RDONLY | O_DIRECTORY);
  if (directory < 0) fail("open its folder");
  const int synced = ::fsync(directory);
  ::close(directory);
  if (synced != 0) fail("fsync its folder");
}

void refuse_overwriting_inputs(const std::filesystem::path& output, const std::string& option,
                               const std::vector<std::filesystem::path>& inputs) {
  struct stat out {};
  if (::stat(output.c_str(), &out) != 0) return;  // a new file is no input
  for (const std::filesystem::path& input : inputs) {
    struct stat in {};
    if (::stat(input.c_str(), &in) == 0 && same_file(out, in)) {
      throw InputError(option + " " + output.string() + ": is the input file " + input.string() +
                       ": refusing to overwrite it");
    }
  }
}

}  // namespace irloc::hal
