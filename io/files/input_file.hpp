#pragma once
// Opening input files safely: never blocking (a FIFO), never unbounded (a link to /dev/zero).

#include <cstddef>
#include <cstdint>
#include <filesystem>
#include <string>

namespace irloc::io {

// An open file descriptor, closed on destruction.
class UniqueFd {
 public:
  UniqueFd() = default;
  explicit UniqueFd(int fd) : fd_(fd) {}
  ~UniqueFd();
  UniqueFd(UniqueFd&& other) noexcept : fd_(other.release()) {}
  UniqueFd& operator=(UniqueFd&& other) noexcept;
  UniqueFd(const UniqueFd&) = delete;
  UniqueFd& operator=(const UniqueFd&) = delete;

  int get() const { return fd_; }
  int release() {
    const int fd = fd_;
    fd_ = -1;
    return fd;
  }

 private:
  int fd_ = -1;
};

struct InputFile {
  UniqueFd fd;
  std::uint64_t size = 0;
};

// Opens `path` (a NUL-terminated name) for reading with O_NONBLOCK, so that a FIFO cannot block,
// then checks with fstat that it is a regular file of at most `max_bytes`. Anything else (a
// directory, a FIFO, a device, a larger file) throws InputError naming the path. Allocates
// nothing unless it throws.
InputFile open_input_file(const char* path, std::uint64_t max_bytes);

// The whole content of a regular file of at most `max_bytes` (opened as above).
std::string read_input_file(const std::filesystem::path& path, std::uint64_t max_bytes);

// Reads up to `capacity` bytes of an open file into `buffer`; returns the count read (less only
// at the end of the file). Throws InputError naming `name` on a read error.
std::size_t read_up_to(int fd, std::byte* buffer, std::size_t capacity, const char* name);

}  // namespace irloc::io
