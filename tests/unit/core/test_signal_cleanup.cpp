// core/signal_cleanup: SignalCleanup::new_directory makes a directory and registers it with no
// signal handled between the two (SignalsHeld), so an interrupt in between does not leave it behind.
#include <doctest/doctest.h>
#include <signal.h>
#include <sys/wait.h>
#include <unistd.h>

#include <cstring>
#include <filesystem>
#include <string>

#include "core/error.hpp"
#include "core/signal_cleanup.hpp"
#include "../temp_dir.hpp"

using namespace quadapt;
using quadapt::test::TempDir;
namespace fs = std::filesystem;

namespace {
int g_report_fd = -1;

// new_directory's hook, between mkdtemp and the registration: says which directory was made, then
// the process is sent SIGTERM right there.
void signal_between(const char* path) {
  const size_t n = std::strlen(path);
  if (write(g_report_fd, path, n) != ssize_t(n)) _exit(3);
  close(g_report_fd);
  kill(getpid(), SIGTERM);
}
}  // namespace

TEST_CASE("signal cleanup: a signal between making the temporary directory and registering it removes it") {
  // A forked "tool" (its handler installed, one thread) makes a directory with new_directory and
  // takes SIGTERM after mkdtemp, before the registration. It must end by the signal and leave no
  // directory: the signal is held until the directory is registered, then the handler removes it.
  // Without SignalsHeld in new_directory the handler ran at once, found nothing registered, and
  // the directory stayed (what bamgquad's ffbamg directory was exposed to).
  TempDir t;
  int fds[2];
  REQUIRE(pipe(fds) == 0);
  const pid_t tool = fork();
  REQUIRE(tool >= 0);
  if (tool == 0) {
    close(fds[0]);
    g_report_fd = fds[1];
    install_signal_cleanup();
    try {
      std::string tmpl = t / "made-XXXXXX";
      SignalCleanup reg = SignalCleanup::new_directory(tmpl, signal_between);
    } catch (...) {
      _exit(4);
    }
    _exit(0);  // not reached: the pending SIGTERM is handled when new_directory returns
  }
  close(fds[1]);
  char buf[4096] = {};
  const ssize_t n = read(fds[0], buf, sizeof buf - 1);
  close(fds[0]);
  int st = 0;
  REQUIRE(waitpid(tool, &st, 0) == tool);
  REQUIRE(n > 0);
  const fs::path made(std::string(buf, size_t(n)));
  CHECK(made.parent_path() == t.dir);
  CHECK(WIFSIGNALED(st));
  CHECK(WTERMSIG(st) == SIGTERM);
  CHECK_FALSE(fs::exists(made));
  CHECK(t.entries() == 0);
}

TEST_CASE("signal cleanup: new_directory makes and registers a directory; a failure is an ExternalError") {
  TempDir t;
  std::string tmpl = t / "made-XXXXXX";
  {
    SignalCleanup reg = SignalCleanup::new_directory(tmpl);
    CHECK(fs::is_directory(tmpl));
    CHECK(tmpl.find("XXXXXX") == std::string::npos);
  }
  std::string missing = t / "no/such/dir-XXXXXX";
  CHECK_THROWS_AS(SignalCleanup::new_directory(missing), ExternalError);
  // the thread's signal mask is as before (nothing left blocked)
  sigset_t now;
  pthread_sigmask(SIG_SETMASK, nullptr, &now);
  CHECK_FALSE(sigismember(&now, SIGTERM));
}
