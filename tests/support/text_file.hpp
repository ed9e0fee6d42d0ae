#pragma once
// Whole files as text, for tests that check what a program wrote.

#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>

namespace irloc::test {

inline std::string read_text(const std::filesystem::path& path) {
  std::ifstream in(path, std::ios::binary);
  std::stringstream text;
  text << in.rdbuf();
  return text.str();
}

}  // namespace irloc::test
