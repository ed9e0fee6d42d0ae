#include "io/files/input_file.hpp"

#include <fcntl.h>
#include <sys/stat.h>
#include <unistd.h>

#include <algorithm>
#include <cerrno>
#include <cstring>

#include "io/input_error.hpp"

namespace irloc::io {

UniqueFd::~UniqueFd() {
  if (fd_ >= 0) ::close(fd_);
}

UniqueFd& UniqueFd::operator=(UniqueFd&& other) noexcept {
  if (this != &other) {
    if (fd_ >= 0) ::close(fd_);
    fd_ = other.release();
  }
  return *this;
}

InputFile open_input_file(const char* path, std::uint64_t max_bytes) {
  InputFile file;
  file.fd = UniqueFd(::open(path, O_RDONLY | O_NONBLOCK | O_CLOEXEC | O_NOCTTY));
  if (file.fd.get() < 0) throw InputError(std::string(path) + ": cannot open: " + std::strerror(errno));
  struct stat status {};
  if (::fstat(file.fd.get(), &status) != 0) throw InputError(std::string(path) + ": cannot stat: " + std::strerror(errno));
  if (S_ISDIR(status.st_mode)) throw InputError(std::string(path) + ": is a directory, expected a regular file");
  if (!S_ISREG(status.st_mode)) {
    throw InputError(std::string(path) + ": is a special file (FIFO, device or socket), expected a regular file");
  }
  file.size = static_cast<std::uint64_t>(status.st_size);
  if (file.size > max_bytes) {
    throw InputError(std::string(path) + ": too large: " + std::to_string(file.size) + " bytes, at most " +
                     std::to_string(max_bytes) + " expected");
  }
  return file;
}

std::size_t read_up_to(int fd, std::byte* buffer, std::size_t capacity, const char* name) {
  std::size_t size = 0;
  while (size < capacity) {
    const ssize_t got = ::read(fd, buffer + size, capacity - size);
    if (got < 0 && errno == EINTR) continue;
    if (got < 0) throw InputError(std::string(name) + ": cannot read: " + std::strerror(errno));
    if (got == 0) break;
    size += static_cast<std::size_t>(got);
  }
  return size;
}

std::string read_input_file(const std::filesystem::path& path, std::uint64_t max_bytes) {
  const std::string name = path.string();
  const InputFile file = open_input_file(name.c_str(), max_bytes);
  // One byte more than allowed, to notice a file that grew since fstat.
  std::string text(static_cast<std::size_t>(file.size) + 1, '\0');
  std::size_t size = 0;
  while (true) {
    size += read_up_to(file.fd.get(), reinterpret_cast<std::byte*>(text.data()) + size, text.size() - size, name.c_str());
    if (size < text.size()) break;
    if (text.size() > max_bytes) {
      throw InputError(name + ": too large: more than " + std::to_string(max_bytes) + " bytes");
    }
    text.resize(std::min<std::size_t>(2 * text.size(), static_cast<std::size_t>(max_bytes) + 1));
  }
  text.resize(size);
  return text;
}

}  // namespace irloc::io
