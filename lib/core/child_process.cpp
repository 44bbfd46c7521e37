#include "core/child_process.hpp"

#include <fcntl.h>
#include <pthread.h>
#include <signal.h>
#include <spawn.h>
#include <sys/stat.h>
#include <sys/wait.h>
#include <unistd.h>

#include <cerrno>
#include <cstdlib>
#include <cstring>
#include <filesystem>
#include <optional>
#include <sstream>

#include "core/error.hpp"
#include "core/signal_cleanup.hpp"

extern char** environ;

namespace quadapt {

bool ChildExit::ok() const { return spawn_error == 0 && WIFEXITED(status) && WEXITSTATUS(status) == 0; }

std::string ChildExit::how() const {
  if (spawn_error != 0) return std::strerror(spawn_error);
  return WIFEXITED(status) ? "exit status " + std::to_string(WEXITSTATUS(status))
                           : "signal " + std::to_string(WTERMSIG(status));
}

ChildExit run_child(const std::vector<std::string>& args, const ChildOptions& opt) {
  ChildExit r;
  if (args.empty()) throw Error("run_child: no program");
  posix_spawn_file_actions_t fa;
  posix_spawn_file_actions_init(&fa);
  posix_spawn_file_actions_addopen(&fa, STDIN_FILENO, "/dev/null", O_RDONLY, 0);
  posix_spawn_file_actions_addopen(&fa, STDOUT_FILENO, opt.output.c_str(), O_WRONLY | O_CREAT | O_TRUNC, 0644);
  posix_spawn_file_actions_adddup2(&fa, STDOUT_FILENO, STDERR_FILENO);
  if (!opt.directory.empty()) posix_spawn_file_actions_addchdir_np(&fa, opt.directory.c_str());
  std::vector<std::string> copy = args;
  std::vector<char*> argv;
  for (auto& a : copy) argv.push_back(a.data());
  argv.push_back(nullptr);
  // SIGINT / SIGTERM / SIGHUP held back on this thread from spawning until the child is
  // registered below, and a handler on another thread waits for that (SpawnWindow), so that an
  // interrupt never leaves it running; the child starts with them unblocked.
  std::optional<SignalsHeld> held(std::in_place);
  posix_spawnattr_t attr;
  posix_spawnattr_init(&attr);
  posix_spawnattr_setsigmask(&attr, &held->before());
  posix_spawnattr_setflags(&attr, POSIX_SPAWN_SETSIGMASK);
  pid_t pid = 0;
  r.spawn_error = posix_spawnp(&pid, argv[0], &fa, &attr, argv.data(), environ);
  posix_spawnattr_destroy(&attr);
  posix_spawn_file_actions_destroy(&fa);
  // killed (and waited for) by the signal handler if this process is interrupted meanwhile: it
  // would otherwise run on, writing files that are being removed
  SignalCleanup child = r.spawn_error == 0 ? SignalCleanup::child(pid) : SignalCleanup();
  held.reset();
  if (r.spawn_error != 0) return r;
  while (waitpid(pid, &r.status, 0) < 0)
    if (errno != EINTR)
      throw ExternalError("waiting for " + std::filesystem::path(args[0]).filename().string() + " failed (" +
                          std::strerror(errno) + ")");
  child.release();  // reaped: its pid may be reused from now on
  return r;
}

bool on_path(const std::string& program) {
  auto executable = [](const std::string& p) {
    struct stat st {};
    return ::stat(p.c_str(), &st) == 0 && S_ISREG(st.st_mode) && ::access(p.c_str(), X_OK) == 0;
  };
  if (program.find('/') != std::string::npos) return executable(program);
  const char* path = std::getenv("PATH");
  std::istringstream dirs(path ? path : "");
  for (std::string dir; std::getline(dirs, dir, ':');)
    if (executable((dir.empty() ? std::string(".") : dir) + "/" + program)) return true;
  return false;
}

}  // namespace quadapt
