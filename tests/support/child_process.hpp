#pragma once
// A program (irlocd, irloc-sim, a reference decoder) run as a child process, as a user runs it:
// arguments without a shell, its output to files, extra environment, and signals to send.

#include <sys/types.h>

#include <filesystem>
#include <optional>
#include <string>
#include <utility>
#include <vector>

namespace irloc::test {

struct ChildOptions {
  std::filesystem::path stdout_file;      // empty: this process's stdout
  std::filesystem::path stderr_file;      // empty: this process's stderr
  std::vector<std::string> environment;   // NAME=VALUE entries added to this process's environment
  std::vector<std::pair<int, int>> fds;   // (this process's fd, the child's fd) to hand over
};

class ChildProcess {
 public:
  // arguments[0] is the program's path. Throws std::runtime_error when it cannot be started.
  explicit ChildProcess(std::vector<std::string> arguments, const ChildOptions& options = {});
  // A child still running (a test that failed half-way) is killed, so that none outlives its test.
  ~ChildProcess();
  ChildProcess(const ChildProcess&) = delete;
  ChildProcess& operator=(const ChildProcess&) = delete;

  void signal(int number) const;
  bool running();
  // Waits for the end: the exit status, or 128 + the signal that ended it.
  int wait();

 private:
  // waitpid with `flags`; true once the child has ended (status_ set).
  bool reap(int flags);

  pid_t pid_ = -1;
  std::optional<int> status_;  // once reaped
};

struct ProcessResult {
  int status = -1;  // exit status, or 128 + the signal that ended it
  std::string stderr_text;
};

// Runs the program to its end with stdout discarded and stderr written to `stderr_file`.
ProcessResult run_to_end(std::vector<std::string> arguments, const std::filesystem::path& stderr_file);

}  // namespace irloc::test
