#pragma once
// Running an external program (bamgquad's ffbamg, meshplot's rsvg-convert) as a child process
// that an interrupt never leaves behind (docs/exit-codes.md "Interrupted").
//
// run_child spawns the program directly (posix_spawnp, no shell), with SIGINT / SIGTERM / SIGHUP
// held back from the spawn until the child is registered with the signal-cleanup registry
// (core/signal_cleanup.hpp), so the handler kills and reaps it whenever this process is
// interrupted while it runs; the child itself starts with those signals as this process had them.
// The registration ends when the child has been waited for.
#include <string>
#include <vector>

namespace quadapt {

struct ChildOptions {
  /// The child's standard output and error: this file, created or truncated (standard input is
  /// /dev/null).
  std::string output = "/dev/null";
  /// The child's working directory; empty: this process's.
  std::string directory;
};

struct ChildExit {
  int spawn_error = 0;  ///< errno of a spawn that failed (the program not found: ENOENT); then no status
  int status = 0;       ///< waitpid's status
  /// Spawned, exited normally with status 0.
  bool ok() const;
  /// "exit status N", "signal N", or the spawn's error text.
  std::string how() const;
};

/// Runs argv[0] (searched on PATH) with the arguments argv[1..] and waits for it (above). Throws
/// ExternalError only when waiting fails; a program that cannot be started is spawn_error.
ChildExit run_child(const std::vector<std::string>& argv, const ChildOptions& opt = {});

/// True when `program` names an executable file on PATH (or, when it has a '/', is one).
bool on_path(const std::string& program);

}  // namespace quadapt
