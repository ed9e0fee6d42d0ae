#pragma once
// The live view's secret for its controls on an address other than loopback: made at the first
// start (32 hex digits from the system's random source), kept in a file only its owner may read
// (mode 0600), read again at every later start. `sudo cat FILE` on the robot shows it.

#include <filesystem>
#include <string>

namespace irloc::firmware {

// The token in `path`, creating the file when it does not exist. Throws InputError naming the
// file when it cannot be made or read, when other users may read it, or when it holds no token.
std::string load_or_create_http_token(const std::filesystem::path& path);

}  // namespace irloc::firmware
