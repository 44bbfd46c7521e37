// core/child_process: run_child's exit statuses, output file, working directory and a program
// that cannot be started; on_path; TempFile's removal (core/atomic_file.hpp); a child spawned on
// one thread while another takes the signal (core/signal_cleanup.hpp, SpawnWindow).
#include <doctest/doctest.h>
#include <signal.h>
#include <spawn.h>
#include <sys/wait.h>
#include <unistd.h>

#include <atomic>
#include <cerrno>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <thread>

#include "core/atomic_file.hpp"
#include "core/child_process.hpp"
#include "core/signal_cleanup.hpp"
#include "../temp_dir.hpp"

extern char** environ;

using namespace quadapt;
using quadapt::test::TempDir;
namespace fs = std::filesystem;

TEST_CASE("run_child: exit status, output file, working directory; a missing program is a spawn error") {
  TempDir t;
  ChildOptions o;
  o.output = t / "out.txt";
  o.directory = t.dir.string();
  const ChildExit ok = run_child({"sh", "-c", "pwd; echo err >&2"}, o);
  CHECK(ok.ok());
  std::ifstream in(o.output);
  std::stringstream ss;
  ss << in.rdbuf();
  CHECK(ss.str() == fs::canonical(t.dir).string() + "\nerr\n");  // stdout and stderr, in its directory

  const ChildExit three = run_child({"sh", "-c", "exit 3"});
  CHECK_FALSE(three.ok());
  CHECK(three.how() == "exit status 3");
  const ChildExit killed = run_child({"sh", "-c", "kill -TERM $$"});
  CHECK(killed.how() == "signal 15");

  const ChildExit missing = run_child({"quadapt-no-such-program"});
  CHECK(missing.spawn_error == ENOENT);
  CHECK_FALSE(missing.ok());
}

TEST_CASE("on_path: programs on PATH and executable paths") {
  CHECK(on_path("sh"));
  CHECK_FALSE(on_path("quadapt-no-such-program"));
  CHECK(on_path("/bin/sh"));
  CHECK_FALSE(on_path("/etc/passwd"));  // not executable
}

TEST_CASE("TempFile: removed at scope exit unless released") {
  TempDir t;
  {
    const TempFile f(t / "a.tmp");
    std::ofstream(f.path()) << "x";
    CHECK(fs::exists(f.path()));
  }
  CHECK_FALSE(fs::exists(t / "a.tmp"));
  {
    TempFile f(t / "b.tmp");
    std::ofstream(f.path()) << "x";
    f.release();
  }
  CHECK(fs::exists(t / "b.tmp"));
}

TEST_CASE("signal cleanup: a child spawned on one thread while another takes the signal is killed") {
  // A forked "tool": thread T blocks the signals, spawns `sleep 30` and registers it 0.3 s later
  // (inside a SpawnWindow); the main thread sends the process SIGTERM in between and takes it
  // itself. The handler must wait for the registration and kill the child; without the window it
  // found no child registered and `sleep` ran on (what meshplot's test saw once under load: an
  // OpenMP thread took the signal while the main thread spawned rsvg-convert).
  int fds[2];
  REQUIRE(pipe(fds) == 0);
  const pid_t tool = fork();
  REQUIRE(tool >= 0);
  if (tool == 0) {
    close(fds[0]);
    install_signal_cleanup();
    std::atomic<pid_t> spawned{0};
    std::thread t([&] {
      sigset_t sigs;
      sigemptyset(&sigs);
      for (int s : {SIGINT, SIGTERM, SIGHUP}) sigaddset(&sigs, s);
      pthread_sigmask(SIG_BLOCK, &sigs, nullptr);
      SignalCleanup reg;
      {
        const SpawnWindow window;
        pid_t c = 0;
        char sleep_[] = "sleep", thirty[] = "30";
        char* argv[] = {sleep_, thirty, nullptr};
        if (posix_spawnp(&c, "sleep", nullptr, nullptr, argv, environ) != 0) _exit(3);
        if (write(fds[1], &c, sizeof c) != sizeof c) _exit(3);
        spawned = c;
        usleep(300000);
        reg = SignalCleanup::child(c);
      }
      for (;;) pause();
    });
    while (spawned == 0) usleep(1000);
    kill(getpid(), SIGTERM);  // the main thread takes it (T blocks it)
    for (;;) pause();
  }
  close(fds[1]);
  pid_t child = 0;
  REQUIRE(read(fds[0], &child, sizeof child) == sizeof child);
  close(fds[0]);
  int st = 0;
  REQUIRE(waitpid(tool, &st, 0) == tool);
  CHECK(WIFSIGNALED(st));
  CHECK(WTERMSIG(st) == SIGTERM);
  const bool alive = kill(child, 0) == 0;  // killed and reaped by the handler: gone
  if (alive) kill(child, SIGKILL);         // (the test's own child: not left behind either way)
  CHECK_FALSE(alive);
}
