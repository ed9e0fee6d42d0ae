#pragma once
// Runs a program as a child process on a disk that is "full" past `max_file_bytes`: RLIMIT_FSIZE
// set and SIGXFSZ ignored in the child, so that a write crossing the limit is short and the next
// one fails (EFBIG), as writes on a full disk do (ENOSPC), without root. stderr comes back
// through a pipe, which the limit does not touch; stdout goes to /dev/null. (fork, not
// child_process.hpp's posix_spawn: the limit is set in the child, and only there.)

#include <fcntl.h>
#include <signal.h>
#include <sys/resource.h>
#include <sys/wait.h>
#include <unistd.h>

#include <cerrno>
#include <stdexcept>
#include <string>
#include <vector>

#include "tests/support/child_process.hpp"

namespace irloc::test {

inline ProcessResult run_with_file_size_limit(std::vector<std::string> arguments, rlim_t max_file_bytes) {
  std::vector<char*> argv;
  for (std::string& argument : arguments) argv.push_back(argument.data());
  argv.push_back(nullptr);
  int pipe_fds[2];
  if (::pipe2(pipe_fds, O_CLOEXEC) != 0) throw std::runtime_error("pipe2 failed");
  const pid_t pid = ::fork();
  if (pid < 0) throw std::runtime_error("fork failed");
  if (pid == 0) {  // only async-signal-safe calls until exec
    const rlimit limit{max_file_bytes, max_file_bytes};
    const int null_fd = ::open("/dev/null", O_WRONLY);
    if (::setrlimit(RLIMIT_FSIZE, &limit) != 0 || ::signal(SIGXFSZ, SIG_IGN) == SIG_ERR || null_fd < 0 ||
        ::dup2(null_fd, 1) < 0 || ::dup2(pipe_fds[1], 2) < 0) {
      ::_exit(126);
    }
    ::execv(argv[0], argv.data());
    ::_exit(127);
  }
  ::close(pipe_fds[1]);
  ProcessResult run;
  char buffer[4096];
  for (ssize_t got; (got = ::read(pipe_fds[0], buffer, sizeof buffer)) != 0;) {
    if (got > 0) run.stderr_text.append(buffer, static_cast<std::size_t>(got));
    else if (errno != EINTR) break;
  }
  ::close(pipe_fds[0]);
  int status = 0;
  while (::waitpid(pid, &status, 0) < 0 && errno == EINTR) {
  }
  run.status = WIFEXITED(status) ? WEXITSTATUS(status) : 128 + WTERMSIG(status);
  return run;
}

}  // namespace irloc::test
