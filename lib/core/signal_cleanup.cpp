#include "core/signal_cleanup.hpp"

#include <limits.h>
#include <pthread.h>
#include <signal.h>
#include <stdlib.h>
#include <sys/wait.h>
#include <time.h>
#include <unistd.h>

#include <atomic>
#include <cerrno>
#include <cstring>

#include "core/error.hpp"

namespace quadapt {

namespace {
enum Kind : int { kFile, kDirectory, kChild };
enum State : int { kFree, kFilling, kReady };

// 64 slots: a tool has at most a few temporaries, one ffbamg run (a child, its directory and four
// files) and the report's temporary alive at once.
struct Slot {
  std::atomic<int> state{kFree};
  int kind = kFile;
  pid_t pid = 0;
  char path[PATH_MAX] = {};
};
Slot g_slots[64];
constexpr int kSlots = int(sizeof g_slots / sizeof g_slots[0]);

int claim(int kind, const char* path, pid_t pid) {
  if (path && std::strlen(path) >= PATH_MAX) return -1;
  for (int i = 0; i < kSlots; ++i) {
    int expected = kFree;
    if (!g_slots[i].state.compare_exchange_strong(expected, kFilling)) continue;
    g_slots[i].kind = kind;
    g_slots[i].pid = pid;
    if (path) std::strcpy(g_slots[i].path, path);
    g_slots[i].state.store(kReady, std::memory_order_release);
    return i;
  }
  return -1;
}

// Threads between spawning a child and registering it (SpawnWindow).
std::atomic<int> g_spawning{0};

// Async-signal-safe only: nanosleep, kill, waitpid, unlink, rmdir, sigaction, raise.
void on_signal(int sig) {
  const int saved_errno = errno;
  // a child being spawned by another thread (its signals blocked) is registered in moments
  for (int k = 0; k < 2000 && g_spawning.load(std::memory_order_acquire) > 0; ++k) {
    struct timespec ms {0, 1000000};
    ::nanosleep(&ms, nullptr);
  }
  for (Slot& s : g_slots)
    if (s.state.load(std::memory_order_acquire) == kReady && s.kind == kChild && s.pid > 0) {
      ::kill(s.pid, SIGKILL);
      while (::waitpid(s.pid, nullptr, 0) < 0 && errno == EINTR) {
      }
    }
  for (Slot& s : g_slots)
    if (s.state.load(std::memory_order_acquire) == kReady && s.kind == kFile) ::unlink(s.path);
  for (Slot& s : g_slots)
    if (s.state.load(std::memory_order_acquire) == kReady && s.kind == kDirectory) ::rmdir(s.path);
  // End by the signal itself (status 128 + sig for a shell, and a parent such as make or bash
  // sees an interrupt): default action, then raise; the signal stays blocked in this handler and
  // is delivered as soon as it returns.
  struct sigaction dfl {};
  dfl.sa_handler = SIG_DFL;
  sigemptyset(&dfl.sa_mask);
  ::sigaction(sig, &dfl, nullptr);
  ::raise(sig);
  errno = saved_errno;
}
}  // namespace

SignalCleanup SignalCleanup::file(const std::string& path) { return SignalCleanup(claim(kFile, path.c_str(), 0)); }
SignalCleanup SignalCleanup::directory(const std::string& path) {
  return SignalCleanup(claim(kDirectory, path.c_str(), 0));
}
SignalCleanup SignalCleanup::child(pid_t pid) { return SignalCleanup(claim(kChild, nullptr, pid)); }

SignalCleanup& SignalCleanup::operator=(SignalCleanup&& o) noexcept {
  if (this != &o) {
    release();
    slot_ = o.slot_;
    o.slot_ = -1;
  }
  return *this;
}

void SignalCleanup::release() {
  if (slot_ < 0) return;
  g_slots[slot_].state.store(kFree, std::memory_order_release);
  slot_ = -1;
}

SpawnWindow::SpawnWindow() { g_spawning.fetch_add(1, std::memory_order_acq_rel); }
SpawnWindow::~SpawnWindow() { g_spawning.fetch_sub(1, std::memory_order_acq_rel); }

SignalsHeld::SignalsHeld() {
  sigset_t held;
  sigemptyset(&held);
  for (int sig : {SIGINT, SIGTERM, SIGHUP}) sigaddset(&held, sig);
  pthread_sigmask(SIG_BLOCK, &held, &before_);
  window_.emplace();
}

SignalsHeld::~SignalsHeld() {
  // the window first: a signal pending on this thread is handled as soon as the mask is restored,
  // and its handler would wait for an open window (its own) for 2 s
  window_.reset();
  pthread_sigmask(SIG_SETMASK, &before_, nullptr);
}

SignalCleanup SignalCleanup::new_directory(std::string& tmpl, void (*between)(const char* path)) {
  const SignalsHeld held;
  if (!::mkdtemp(tmpl.data()))
    throw ExternalError("cannot create a temporary directory " + tmpl + " (" + std::strerror(errno) + ")");
  if (between) between(tmpl.c_str());
  return directory(tmpl);
}

void install_signal_cleanup() {
  for (int sig : {SIGINT, SIGTERM, SIGHUP}) {
    struct sigaction old {};
    if (::sigaction(sig, nullptr, &old) != 0 || old.sa_handler == SIG_IGN) continue;
    struct sigaction sa {};
    sa.sa_handler = on_signal;
    sigemptyset(&sa.sa_mask);
    for (int other : {SIGINT, SIGTERM, SIGHUP}) sigaddset(&sa.sa_mask, other);  // one cleanup at a time
    ::sigaction(sig, &sa, nullptr);
  }
  // A file-size limit (ulimit -f, batch systems): the write that passes it fails with EFBIG and
  // the tool reports it (exit 2, the temporary removed) instead of dying by SIGXFSZ with a
  // truncated temporary left behind.
  ::signal(SIGXFSZ, SIG_IGN);
}

}  // namespace quadapt
