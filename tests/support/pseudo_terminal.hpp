#pragma once
// A real pseudo-terminal pair for serial tests: the code under test opens slave_path() as it
// would /dev/ttyAMA0; the test reads what arrives on the master side.

#include <fcntl.h>
#include <poll.h>
#include <stdlib.h>
#include <unistd.h>

#include <cstdint>
#include <stdexcept>
#include <string>
#include <vector>

namespace irloc::test {

class PseudoTerminal {
 public:
  PseudoTerminal() {
    master_ = ::posix_openpt(O_RDWR | O_NOCTTY | O_CLOEXEC);
    if (master_ < 0 || ::grantpt(master_) != 0 || ::unlockpt(master_) != 0) throw std::runtime_error("cannot open a pty");
    char name[128];
    if (::ptsname_r(master_, name, sizeof name) != 0) throw std::runtime_error("ptsname_r failed");
    slave_path_ = name;
  }
  ~PseudoTerminal() {
    if (master_ >= 0) ::close(master_);
  }
  PseudoTerminal(const PseudoTerminal&) = delete;
  PseudoTerminal& operator=(const PseudoTerminal&) = delete;

  const std::string& slave_path() const { return slave_path_; }
  int master_fd() const { return master_; }

  // Everything readable on the master within `timeout_ms` of quiet.
  std::vector<std::uint8_t> read_available(int timeout_ms = 200) const {
    std::vector<std::uint8_t> bytes;
    std::uint8_t chunk[4096];
    pollfd request{master_, POLLIN, 0};
    while (::poll(&request, 1, timeout_ms) > 0 && (request.revents & POLLIN)) {
      const ssize_t got = ::read(master_, chunk, sizeof chunk);
      if (got <= 0) break;
      bytes.insert(bytes.end(), chunk, chunk + got);
    }
    return bytes;
  }

 private:
  int master_ = -1;
  std::string slave_path_;
};

}  // namespace irloc::test
