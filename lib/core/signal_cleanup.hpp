#pragma once
// Cleaning up after SIGINT / SIGTERM / SIGHUP (docs/exit-codes.md: a temporary is removed on
// failure, and an interrupt is a failure). SIGXFSZ (a file-size limit) is ignored, so the write
// that passes the limit fails with EFBIG and is reported like a full disk.
//
// Library code that creates something the process must not leave behind registers it for the
// time it exists: a TempFile (core/atomic_file.hpp: atomic_write's temporary, meshplot's SVG for
// rsvg-convert), run_child its child process (core/child_process.hpp: bamgquad's ffbamg,
// meshplot's rsvg-convert), run_ffbamg its private directory. The tools' runner installs the handler (install_signal_cleanup; library code never
// installs handlers). On a signal the handler kills the registered children (SIGKILL, then
// waits for them, so they write nothing more), unlinks the registered files, removes the
// registered directories, and re-raises the signal with its default action: the process ends by
// that signal, which a shell reports as status 128 + N (130 for SIGINT, 143 for SIGTERM).
//
// The registry is a fixed array of slots holding C strings and pids, written before a slot is
// published (an atomic flag), so the handler uses only async-signal-safe calls (nanosleep, kill, waitpid,
// unlink, rmdir, raise) and never allocates.
#include <signal.h>
#include <sys/types.h>

#include <optional>
#include <string>

namespace quadapt {

/// One registered entry, released on destruction (after a rename, or once the directory or the
/// child is gone). Move-only. When the registry is full the entry is simply not registered
/// (the interrupt then leaves it behind, as before).
class SignalCleanup {
 public:
  SignalCleanup() = default;
  /// A file the handler unlinks.
  static SignalCleanup file(const std::string& path);
  /// A directory the handler removes after unlinking the files (rmdir removes only an empty
  /// directory: register the files in it too).
  static SignalCleanup directory(const std::string& path);
  /// A child process the handler kills (before anything is unlinked).
  static SignalCleanup child(pid_t pid);
  /// Makes a private directory by mkdtemp(tmpl) (tmpl ends in "XXXXXX", which becomes the name)
  /// and registers it as directory(tmpl), with the signals held across both (SignalsHeld): an
  /// interrupt between the two left the directory behind. Throws ExternalError when mkdtemp fails.
  /// `between` (a test hook) runs after the directory is made, before it is registered.
  static SignalCleanup new_directory(std::string& tmpl, void (*between)(const char* path) = nullptr);

  SignalCleanup(SignalCleanup&& o) noexcept : slot_(o.slot_) { o.slot_ = -1; }
  SignalCleanup& operator=(SignalCleanup&& o) noexcept;
  SignalCleanup(const SignalCleanup&) = delete;
  SignalCleanup& operator=(const SignalCleanup&) = delete;
  ~SignalCleanup() { release(); }

  /// Unregisters now (e.g. right after the temporary was renamed to the output).
  void release();

 private:
  explicit SignalCleanup(int slot) : slot_(slot) {}
  int slot_ = -1;
};

/// Held by a thread while it spawns a child and registers it (SignalCleanup::child), with
/// SIGINT / SIGTERM / SIGHUP blocked on that thread: a handler running meanwhile on another thread
/// (a signal sent to the process goes to any thread that does not block it, e.g. an OpenMP worker)
/// waits for the window to close, up to 2 s, before it kills the registered children — else the
/// child spawned in the window is not registered yet and is left running.
class SpawnWindow {
 public:
  SpawnWindow();
  ~SpawnWindow();
  SpawnWindow(const SpawnWindow&) = delete;
  SpawnWindow& operator=(const SpawnWindow&) = delete;
};

/// SIGINT / SIGTERM / SIGHUP blocked on this thread and a SpawnWindow open for as long as it lives:
/// held by whatever creates something and registers it (run_child's child, new_directory's
/// directory), so that no signal is handled between the two. A signal arriving meanwhile is handled
/// once it is gone (the window is closed first, then the thread's mask restored). `before()` is the
/// thread's mask before (a child starts with it).
class SignalsHeld {
 public:
  SignalsHeld();
  ~SignalsHeld();
  SignalsHeld(const SignalsHeld&) = delete;
  SignalsHeld& operator=(const SignalsHeld&) = delete;
  const sigset_t& before() const { return before_; }

 private:
  sigset_t before_;
  std::optional<SpawnWindow> window_;
};

/// Installs the handler for SIGINT, SIGTERM and SIGHUP (those left at their default action:
/// an ignored SIGINT, e.g. under nohup, stays ignored). Called once per process by the runner.
void install_signal_cleanup();

}  // namespace quadapt
