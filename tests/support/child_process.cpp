#include "tests/support/child_process.hpp"

#include <fcntl.h>
#include <signal.h>
#include <spawn.h>
#include <sys/wait.h>

#include <cerrno>
#include <cstring>
#include <stdexcept>

#include "tests/support/text_file.hpp"

extern char** environ;

namespace irloc::test {

ChildProcess::ChildProcess(std::vector<std::string> arguments, const ChildOptions& options) {
  std::vector<char*> argv;
  for (std::string& argument : arguments) argv.push_back(argument.data());
  argv.push_back(nullptr);
  std::vector<std::string> environment = options.environment;
  std::vector<char*> envp;
  for (char** entry = environ; *entry; ++entry) envp.push_back(*entry);
  for (std::string& entry : environment) envp.push_back(entry.data());
  envp.push_back(nullptr);

  posix_spawn_file_actions_t actions;
  posix_spawn_file_actions_init(&actions);
  for (const auto& [from, to] : options.fds) posix_spawn_file_actions_adddup2(&actions, from, to);
  constexpr int kCreate = O_WRONLY | O_CREAT | O_TRUNC;
  if (!options.stdout_file.empty()) posix_spawn_file_actions_addopen(&actions, 1, options.stdout_file.c_str(), kCreate, 0644);
  if (!options.stderr_file.empty()) posix_spawn_file_actions_addopen(&actions, 2, options.stderr_file.c_str(), kCreate, 0644);
  const int error = posix_spawn(&pid_, argv[0], &actions, nullptr, argv.data(), envp.data());
  posix_spawn_file_actions_destroy(&actions);
  if (error != 0) throw std::runtime_error(arguments[0] + ": cannot start: " + std::strerror(error));
}

ChildProcess::~ChildProcess() {
  if (status_) return;
  ::kill(pid_, SIGKILL);
  reap(0);
}

void ChildProcess::signal(int number) const { ::kill(pid_, number); }

bool ChildProcess::running() { return !status_ && !reap(WNOHANG); }

int ChildProcess::wait() {
  if (!status_ && !reap(0)) throw std::runtime_error(std::string("waitpid: ") + std::strerror(errno));
  return *status_;
}

bool ChildProcess::reap(int flags) {
  int raw = 0;
  pid_t reaped;
  while ((reaped = ::waitpid(pid_, &raw, flags)) < 0 && errno == EINTR) {
  }
  if (reaped != pid_) return false;
  status_ = WIFEXITED(raw) ? WEXITSTATUS(raw) : 128 + WTERMSIG(raw);
  return true;
}

ProcessResult run_to_end(std::vector<std::string> arguments, const std::filesystem::path& stderr_file) {
  ChildOptions options;
  options.stdout_file = "/dev/null";
  options.stderr_file = stderr_file;
  ChildProcess child(std::move(arguments), options);
  const int status = child.wait();
  return {status, read_text(stderr_file)};
}

}  // namespace irloc::test
