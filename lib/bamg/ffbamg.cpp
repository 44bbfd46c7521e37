#include "bamg/ffbamg.hpp"

#include <fcntl.h>
#include <spawn.h>
#include <sys/wait.h>
#include <unistd.h>

#include <cerrno>
#include <chrono>
#include <cstdlib>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <sstream>

#include "core/error.hpp"

extern char** environ;

namespace quadapt {

namespace {
namespace fs = std::filesystem;

// A private temporary directory, removed with everything in it on destruction.
struct TempDir {
  fs::path path;
  TempDir() {
    std::string tmpl = (fs::temp_directory_path() / "quadapt-ffbamg-XXXXXX").string();
    if (!mkdtemp(tmpl.data())) throw ExternalError("cannot create a temporary directory for ffbamg");
    path = tmpl;
  }
  ~TempDir() {
    std::error_code ec;
    fs::remove_all(path, ec);
  }
};

std::string tail_of(const fs::path& p, size_t max_chars = 600) {
  std::ifstream f(p);
  std::stringstream s;
  s << f.rdbuf();
  std::string t = s.str();
  if (t.size() > max_chars) t = "..." + t.substr(t.size() - max_chars);
  for (char& c : t)
    if (c == '\n') c = ' ';
  return t;
}
}  // namespace

FfbamgResult run_ffbamg(const InriaMesh& background, const std::vector<Eigen::Matrix2d>& metric,
                        const FfbamgOptions& opt) {
  if (metric.size() != background.vertices.size())
    throw Error("run_ffbamg: " + std::to_string(metric.size()) + " metrics for " +
                std::to_string(background.vertices.size()) + " vertices");
  std::string exe = opt.executable;
  if (exe.empty()) {
    const char* env = std::getenv("QUADAPT_FFBAMG");
    exe = env && *env ? env : "ffbamg";
  }
  TempDir dir;
  const fs::path bg = dir.path / "background.mesh", mtr = dir.path / "background.mtr",
                 out = dir.path / "out.mesh", log = dir.path / "ffbamg.log";
  write_inria_mesh(background, bg.string());
  write_bamg_metric(metric, mtr.string());

  std::vector<std::string> args = {exe, "-b", bg.string(), "-M", mtr.string(), "-o", out.string(),
                                   "-nbv", std::to_string(opt.max_vertices), "-v", "1",
                                   "-NbSmooth", std::to_string(opt.smoothing_iterations)};
  if (opt.split_boundary_edges) args.push_back("-splitpbedge");
  if (opt.gradation > 0) {
    std::ostringstream r;
    r << opt.gradation;
    args.insert(args.end(), {"-ratio", r.str()});
  }
  FfbamgResult res;
  for (const auto& a : args) res.command += (res.command.empty() ? "" : " ") + fs::path(a).filename().string();

  posix_spawn_file_actions_t fa;
  posix_spawn_file_actions_init(&fa);
  posix_spawn_file_actions_addopen(&fa, STDIN_FILENO, "/dev/null", O_RDONLY, 0);
  posix_spawn_file_actions_addopen(&fa, STDOUT_FILENO, log.c_str(), O_WRONLY | O_CREAT | O_TRUNC, 0644);
  posix_spawn_file_actions_adddup2(&fa, STDOUT_FILENO, STDERR_FILENO);
  posix_spawn_file_actions_addchdir_np(&fa, dir.path.c_str());
  std::vector<char*> argv;
  for (auto& a : args) argv.push_back(a.data());
  argv.push_back(nullptr);
  const auto t0 = std::chrono::steady_clock::now();
  pid_t pid = 0;
  int rc = posix_spawnp(&pid, exe.c_str(), &fa, nullptr, argv.data(), environ);
  posix_spawn_file_actions_destroy(&fa);
  if (rc != 0)
    throw ExternalError("cannot run '" + exe + "' (FreeFEM's BAMG; Debian package freefem++): " +
                        std::string(strerror(rc)));
  int status = 0;
  while (waitpid(pid, &status, 0) < 0)
    if (errno != EINTR) throw ExternalError("waiting for ffbamg failed");
  res.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
  if (!WIFEXITED(status) || WEXITSTATUS(status) != 0 || !fs::exists(out)) {
    std::string how = WIFEXITED(status) ? "exit status " + std::to_string(WEXITSTATUS(status))
                                        : "signal " + std::to_string(WTERMSIG(status));
    throw ExternalError("ffbamg failed (" + how + "): " + tail_of(log));
  }
  try {
    res.mesh = read_inria_mesh(out.string());
  } catch (const InputError& e) {
    throw ExternalError(std::string("ffbamg wrote an unreadable mesh: ") + e.what());
  }
  if (res.mesh.triangles.empty()) throw ExternalError("ffbamg produced no triangles: " + tail_of(log));
  return res;
}

}  // namespace quadapt
