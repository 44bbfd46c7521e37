#include "bamg/ffbamg.hpp"

#include <cctype>
#include <chrono>
#include <cmath>
#include <cstdlib>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <vector>

#include "core/child_process.hpp"
#include "core/error.hpp"
#include "core/signal_cleanup.hpp"

namespace quadapt {

namespace {
namespace fs = std::filesystem;

// A private temporary directory, removed with everything in it on destruction. On SIGINT /
// SIGTERM (core/signal_cleanup) the handler unlinks the files named by file() and removes it.
struct TempDir {
  fs::path path;
  SignalCleanup on_signal;
  std::vector<SignalCleanup> files_on_signal;
  TempDir() {
    std::string tmpl = (fs::temp_directory_path() / "quadapt-ffbamg-XXXXXX").string();
    on_signal = SignalCleanup::new_directory(tmpl);  // made and registered with no signal between
    path = tmpl;
  }
  /// The path of `name` in the directory, registered for removal on a signal.
  fs::path file(const std::string& name) {
    files_on_signal.push_back(SignalCleanup::file((path / name).string()));
    return path / name;
  }
  ~TempDir() {
    std::error_code ec;
    fs::remove_all(path, ec);
  }
};

// One line of ffbamg's output that says what went wrong: the first that mentions an error
// ("Err mesh vertices 290 is not in a triangle"), else the last non-empty one; blanks collapsed,
// at most 160 characters (its whole log ran to ~500 characters of banner and C++ abort text).
std::string cause_in(const fs::path& log) {
  std::ifstream f(log);
  std::string line, first_error, last;
  while (std::getline(f, line)) {
    std::string t;
    for (char c : line) {
      if (!std::isspace(static_cast<unsigned char>(c))) t += c;
      else if (!t.empty() && t.back() != ' ') t += ' ';
    }
    while (!t.empty() && t.back() == ' ') t.pop_back();
    if (t.empty()) continue;
    last = t;
    if (first_error.empty() && (t.find("Err") != std::string::npos || t.find("rror") != std::string::npos))
      first_error = t;
  }
  std::string cause = first_error.empty() ? last : first_error;
  if (cause.empty()) return "no output";
  if (cause.size() > 160) cause = cause.substr(0, 157) + "...";
  return cause;
}
/// BAMG works in a frame near the origin: a unit square moved to [1e6, 1e6 + 1]^2 made ffbamg
/// abort ("Fatal error in the mesh generator 1001") on its second calibration run (a review,
/// session 35). So a coordinate whose centre lies more than 4 extents from 0 is written shifted,
/// x' = x - shift, shift a multiple of the extent rounded up to a power of two (x - shift exact,
/// and an exact translation by such a multiple gives ffbamg the same bytes); other coordinates
/// are written as they are (bit for bit as before). No scaling: ffbamg writes ~12 significant
/// digits, so a scaled unit would move wall nodes off a wall at x = 1e6 by 3e-7 (a review);
/// shifted, the output keeps the digits it had at the origin.
Vec2 bamg_shift(const std::vector<Vec2>& v) {
  if (v.empty()) return Vec2::Zero();
  Vec2 lo = v[0], hi = v[0];
  for (const auto& x : v) lo = lo.cwiseMin(x), hi = hi.cwiseMax(x);
  const double extent = (hi - lo).maxCoeff();
  if (!(extent > 0) || !std::isfinite(extent)) return Vec2::Zero();
  const double unit = std::exp2(std::ceil(std::log2(extent)));
  Vec2 shift = Vec2::Zero();
  for (int k = 0; k < 2; ++k)
    if (std::abs(0.5 * (lo[k] + hi[k])) > 4 * extent) shift[k] = unit * std::floor(lo[k] / unit);
  return shift;
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
  const fs::path bg = dir.file("background.mesh"), mtr = dir.file("background.mtr"), out = dir.file("out.mesh"),
                 log = dir.file("ffbamg.log");
  const Vec2 shift = bamg_shift(background.vertices);
  if (shift == Vec2::Zero()) {
    write_inria_mesh(background, bg.string());
  } else {
    InriaMesh b = background;
    for (auto& x : b.vertices) x -= shift;
    write_inria_mesh(b, bg.string());
  }
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
  ChildOptions co;
  co.output = log.string();
  co.directory = dir.path.string();
  const auto t0 = std::chrono::steady_clock::now();
  // killed by the signal handler if this process is interrupted meanwhile (core/child_process):
  // it would otherwise run on, writing into a directory that is being removed
  const ChildExit ex = run_child(args, co);
  if (ex.spawn_error != 0)
    throw FfbamgNotRunnable("cannot run '" + exe + "' (FreeFEM's BAMG; Debian package freefem++): " + ex.how());
  res.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
  if (!ex.ok() || !fs::exists(out)) throw ExternalError("ffbamg failed (" + ex.how() + "): " + cause_in(log));
  try {
    res.mesh = read_inria_mesh(out.string());
  } catch (const InputError& e) {
    throw ExternalError(std::string("ffbamg wrote an unreadable mesh: ") + e.what());
  }
  if (res.mesh.triangles.empty()) throw ExternalError("ffbamg produced no triangles: " + cause_in(log));
  if (shift != Vec2::Zero())
    for (auto& x : res.mesh.vertices) x += shift;
  return res;
}

}  // namespace quadapt
