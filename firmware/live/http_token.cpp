#include "firmware/live/http_token.hpp"

#include <fcntl.h>
#include <sys/stat.h>
#include <unistd.h>

#include <cerrno>
#include <cstring>
#include <random>

#include "io/files/input_file.hpp"
#include "io/files/output_file.hpp"
#include "io/input_error.hpp"

namespace irloc::firmware {
namespace {

constexpr std::size_t kTokenDigits = 32;

std::string new_token() {
  std::random_device random;  // the system's random source (getrandom)
  static const char kHex[] = "0123456789abcdef";
  std::string token;
  while (token.size() < kTokenDigits) {
    const unsigned int bits = random();
    for (int k = 0; k < 8 && token.size() < kTokenDigits; ++k) token += kHex[(bits >> (4 * k)) & 15u];
  }
  return token;
}

}  // namespace

std::string load_or_create_http_token(const std::filesystem::path& path) {
  const io::UniqueFd created(::open(path.c_str(), O_WRONLY | O_CREAT | O_EXCL | O_NOFOLLOW | O_CLOEXEC, 0600));
  if (created.get() >= 0) {
    const std::string token = new_token();
    const std::string line = token + "\n";
    io::write_all(created.get(), line.data(), line.size(), path.string());
    return token;
  }
  if (errno != EEXIST) throw io::InputError(path.string() + ": cannot create the live view's token: " + std::strerror(errno));
  struct stat status {};
  if (::stat(path.c_str(), &status) != 0) throw io::InputError(path.string() + ": cannot read: " + std::strerror(errno));
  if ((status.st_mode & 077) != 0) {
    throw io::InputError(path.string() + ": the live view's token may be read by other users: chmod 600 it");
  }
  std::string token = io::read_input_file(path, 256);
  while (!token.empty() && (token.back() == '\n' || token.back() == '\r' || token.back() == ' ')) token.pop_back();
  if (token.size() < 16 || token.find_first_of(" \t\r\n") != std::string::npos) {
    throw io::InputError(path.string() + ": expected one token of at least 16 characters on one line");
  }
  return token;
}

}  // namespace irloc::firmware
