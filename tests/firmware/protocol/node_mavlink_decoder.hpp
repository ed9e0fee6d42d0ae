#pragma once
// node-mavlink as the tests' independent MAVLink decoder (mavlink_decoder/decode.mjs): it reads a
// pty master (handed over as its fd 3) until the writer's side closes, and prints one line per
// decoded message; `arguments` are decode.mjs's options (--timesync TS1).

#include <filesystem>
#include <fstream>
#include <string>
#include <vector>

#include <gtest/gtest.h>

#include "tests/support/child_process.hpp"

namespace irloc::test {

class NodeMavlinkDecoder {
 public:
  NodeMavlinkDecoder(int master_fd, const std::filesystem::path& output, const std::vector<std::string>& arguments = {})
      : output_(output), node_(command(arguments), options(master_fd, output)) {}

  std::vector<std::string> finish() {
    EXPECT_EQ(node_.wait(), 0) << "the decoder failed";
    std::ifstream in(output_);
    std::vector<std::string> lines;
    for (std::string line; std::getline(in, line);) lines.push_back(line);
    return lines;
  }

 private:
  static std::vector<std::string> command(const std::vector<std::string>& arguments) {
    std::vector<std::string> all{IRLOC_NODE, IRLOC_MAVLINK_DECODER};
    all.insert(all.end(), arguments.begin(), arguments.end());
    return all;
  }
  static ChildOptions options(int master_fd, const std::filesystem::path& output) {
    ChildOptions options;
    options.stdout_file = output;
    options.fds = {{master_fd, 3}};
    return options;
  }

  std::filesystem::path output_;
  ChildProcess node_;
};

}  // namespace irloc::test
