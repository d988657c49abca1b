#include "matpoint/core/subprocess.hpp"

#include <fcntl.h>
#include <spawn.h>
#include <sys/wait.h>
#include <unistd.h>

#include <cerrno>
#include <cstring>

extern char** environ;

namespace matpoint {

namespace {

constexpr std::size_t kStderrKept = 2000;  // the end of a traceback names the real error

/// Reads a pipe to its end, keeping only the last kStderrKept characters.
std::string drain_tail(int fd) {
  std::string tail;
  char buffer[4096];
  for (;;) {
    const ssize_t n = read(fd, buffer, sizeof buffer);
    if (n < 0 && errno == EINTR) continue;
    if (n <= 0) break;
    tail.append(buffer, static_cast<std::size_t>(n));
    if (tail.size() > 2 * kStderrKept) tail.erase(0, tail.size() - kStderrKept);
  }
  if (tail.size() > kStderrKept) tail = "..." + tail.substr(tail.size() - kStderrKept);
  while (!tail.empty() && (tail.back() == '\n' || tail.back() == ' ')) tail.pop_back();
  return tail;
}

std::string exit_reason(int status) {
  if (WIFEXITED(status)) return "exited with status " + std::to_string(WEXITSTATUS(status));
  if (WIFSIGNALED(status)) return std::string("was killed by signal ") + strsignal(WTERMSIG(status));
  return "ended abnormally";
}

}  // namespace

std::string run_program(const std::vector<std::string>& argv) {
  if (argv.empty()) return "no program given";
  std::vector<char*> args;
  for (const auto& a : argv) args.push_back(const_cast<char*>(a.c_str()));
  args.push_back(nullptr);

  int err_pipe[2];
  if (pipe2(err_pipe, O_CLOEXEC) != 0) return std::string("cannot create a pipe: ") + std::strerror(errno);
  posix_spawn_file_actions_t actions;
  posix_spawn_file_actions_init(&actions);
  posix_spawn_file_actions_addopen(&actions, STDIN_FILENO, "/dev/null", O_RDONLY, 0);
  posix_spawn_file_actions_addopen(&actions, STDOUT_FILENO, "/dev/null", O_WRONLY, 0);
  posix_spawn_file_actions_adddup2(&actions, err_pipe[1], STDERR_FILENO);
  pid_t pid = 0;
  const bool search = argv[0].find('/') == std::string::npos;
  const int spawned = search ? posix_spawnp(&pid, args[0], &actions, nullptr, args.data(), environ)
                             : posix_spawn(&pid, args[0], &actions, nullptr, args.data(), environ);
  posix_spawn_file_actions_destroy(&actions);
  close(err_pipe[1]);
  if (spawned != 0) {
    close(err_pipe[0]);
    return "cannot start " + argv[0] + ": " + std::strerror(spawned);
  }
  const std::string err = drain_tail(err_pipe[0]);
  close(err_pipe[0]);
  int status = 0;
  while (waitpid(pid, &status, 0) < 0)
    if (errno != EINTR) return "cannot wait for " + argv[0] + ": " + std::strerror(errno);
  if (WIFEXITED(status) && WEXITSTATUS(status) == 0) return "";
  // posix_spawnp reports a missing program as exit status 127 of the child on glibc.
  std::string reason = argv[0] + " " + exit_reason(status);
  if (!err.empty()) reason += ":\n" + err;
  return reason;
}

std::string run_python_script(const std::filesystem::path& script, const std::vector<std::string>& args) {
  if (!std::filesystem::is_regular_file(script)) return "script not found: " + script.string();
  std::vector<std::string> argv{std::filesystem::exists("/usr/bin/python3") ? "/usr/bin/python3" : "python3",
                                script.string()};
  argv.insert(argv.end(), args.begin(), args.end());
  return run_program(argv);
}

}  // namespace matpoint
