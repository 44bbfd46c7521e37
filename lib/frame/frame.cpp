#include "frame/frame.hpp"

#include <Eigen/Dense>
#include <cmath>
#include <sstream>

#include "core/error.hpp"
#include "core/format.hpp"
#include "io/msh.hpp"
#include "mesh/canonical.hpp"
#include "mesh/label.hpp"

namespace quadapt {

namespace {

// Target cells per unit metric area |det M| (quadapt): a cell has area (2h1)(2h2) = 4 / |det M|.
constexpr double kCellsPerMetricArea = 0.25;

}  // namespace

// Half-axis (quadapt) M per file M: a PHiLiP edge of length h is a half-axis of h/2.
double quadapt_factor(SizeConvention c) { return c == SizeConvention::Philip ? 2.0 : 1.0; }

std::string to_string(SizeConvention c) { return c == SizeConvention::Philip ? "philip" : "quadapt"; }

SizeConvention parse_size_convention(const std::string& word, const std::string& source) {
  if (word == "quadapt") return SizeConvention::Quadapt;
  if (word == "philip") return SizeConvention::Philip;
  throw InputError(source, "unknown frame size convention '" + word + "' (quadapt or philip)");
}

SizeConvention stated_convention(const Mesh& m, const std::string& path) {
  return m.frame_convention.empty() ? SizeConvention::Philip : parse_size_convention(m.frame_convention, path);
}

double cell_density(double h) { return 1.0 / (4 * h * h); }
double size_for_density(double d) { return 0.5 / std::sqrt(d); }

Mat2 frame_inverse(double h, double rho, double theta) {
  const double h1 = h * std::sqrt(rho), h2 = h / std::sqrt(rho);
  const double c = std::cos(theta), s = std::sin(theta);
  Mat2 M;
  M << c / h1, s / h1, -s / h2, c / h2;
  return M;
}

std::array<double, 9> vinv_components(const Mat2& M) {
  return {{M(0, 0), M(0, 1), 0.0, M(1, 0), M(1, 1), 0.0, 0.0, 0.0, 0.0}};
}

Mat2 without_reflection(const Mat2& M) {
  Mat2 r = M;
  if (M.determinant() < 0) r.row(1) *= -1.0;
  return r;
}

std::pair<Vec2, Vec2> frame_axes(const Mat2& M) {
  const double det = M.determinant();
  if (!M.allFinite() || !std::isfinite(det) || std::abs(det) <= 1e-300 * M.cwiseAbs().maxCoeff())
    throw NumericalError("frame matrix M = V^-1 is singular or not finite");
  const Mat2 V = M.inverse();
  return {V.col(0), V.col(1)};
}

std::vector<Mat2> Frame::oriented() const {
  std::vector<Mat2> r(M.size());
  for (size_t c = 0; c < M.size(); ++c) r[c] = without_reflection(M[c]);
  return r;
}

double Frame::cell_metric_factor() { return 0.5; }  // = sqrt(kCellsPerMetricArea)

double Frame::target_cells() const {
  double n = 0;
  for (int c = 0; c < num_cells(); ++c) n += std::abs(cell_area(mesh, c)) * std::abs(M[c].determinant()) * kCellsPerMetricArea;
  return n;
}

Frame Frame::scaled(double f) const {
  if (!(f > 0) || !std::isfinite(f)) throw InputError("", "frame scale factor must be positive and finite");
  Frame r = *this;
  for (Mat2& m : r.M) m *= f;
  return r;
}

double Frame::scale_for_cells(double cells) const {
  const double now = target_cells();
  if (!(cells > 0) || !(now > 0)) throw InputError("", "a frame rescale needs positive cell counts");
  return std::sqrt(cells / now);
}

double cells_for_complexity(double complexity, int degree) {
  if (!(complexity > 0) || degree < 0) throw InputError("", "complexity must be positive and the degree >= 0");
  return complexity / ((degree + 1.0) * (degree + 1.0));
}

Frame frame_from_mesh(const Mesh& m, const std::string& path, std::optional<SizeConvention> convention) {
  const CellField* f = m.cell_field("Vinv");
  if (!f) {
    throw InputError(path, "no cell field \"Vinv\" (the frame M = V^-1); fields present: " + m.field_list());
  }
  if (f->ncomp != 9) throw InputError(path, "field \"Vinv\" has " + std::to_string(f->ncomp) + " components, expected 9");
  if (f->values.size() != static_cast<size_t>(m.num_cells()) * 9)
    throw InputError(path, "field \"Vinv\" has " + std::to_string(f->num_cells()) + " values for " +
                               std::to_string(m.num_cells()) + " cells");
  Frame fr;
  fr.source = convention ? *convention : stated_convention(m, path);
  const double k = quadapt_factor(fr.source);
  fr.M.resize(m.num_cells());
  for (int c = 0; c < m.num_cells(); ++c) {
    Mat2 M;
    M << (*f)(c, 0), (*f)(c, 1), (*f)(c, 3), (*f)(c, 4);
    if (!M.allFinite()) throw InputError(path, "non-finite frame \"Vinv\" in " + cell_label(m, c));
    // |det M| > 1e-12 |M|_F^2: the stretch sigma_max / sigma_min below ~1e12 (a conditioning
    // bound, so the message names the stretch; det M alone says nothing when M is large)
    const double nrm = M.squaredNorm(), det = M.determinant();
    if (!(nrm > 0) || !(std::abs(det) > 1e-12 * nrm)) {
      std::string why;
      if (!(nrm > 0)) {
        why = "M = 0";
      } else if (!std::isfinite(nrm) || !std::isfinite(det)) {
        why = "entries too large: |M|^2 overflows";
      } else {
        const Eigen::Vector2d s = Eigen::JacobiSVD<Mat2>(M).singularValues();
        why = "det M = " + sci(det) + ", stretch sigma_max/sigma_min = " + sci(s(0) / s(1)) +
              ", more than the 1e12 a frame may have";
      }
      throw InputError(path, "singular frame \"Vinv\" (" + why + ") in " + cell_label(m, c));
    }
    fr.M[c] = k * M;
  }
  fr.mesh = m;
  return fr;
}

Frame read_frame(const std::string& path, std::optional<SizeConvention> convention) {
  // validated in the file's numbering (messages name its cells), then put in canonical order
  return canonical_frame(frame_from_mesh(read_valid_msh(path, ValidateOptions::fields({"Vinv"})), path, convention));
}

Frame canonical_frame(Frame f) {
  Renumbering r;
  f.mesh = canonical_order(f.mesh, &r);
  std::vector<Mat2> M(f.M.size());
  for (size_t c = 0; c < M.size(); ++c) M[c] = f.M[static_cast<size_t>(r.old_cell[c])];
  f.M = std::move(M);
  return f;
}

void set_frame_field(Mesh& m, const std::vector<Mat2>& M) {
  if (static_cast<int>(M.size()) != m.num_cells()) throw Error("set_frame_field: one M per cell expected");
  CellField v;
  v.name = "Vinv";
  v.ncomp = 9;
  v.values.resize(M.size() * 9);
  for (size_t c = 0; c < M.size(); ++c) {
    const auto comp = vinv_components(M[c]);
    for (int i = 0; i < 9; ++i) v.values[c * 9 + i] = comp[i];
  }
  m.set_field(std::move(v));
  m.frame_convention = to_string(SizeConvention::Quadapt);
}

Mesh frame_mesh(const Frame& f) {
  Mesh m = f.mesh;
  m.clear_fields();
  set_frame_field(m, f.M);
  return m;
}

void write_frame(const Frame& f, const std::string& path) { write_msh(frame_mesh(f), path); }
void write_frame(const Frame& f, const std::string& path, OutputBatch& batch) {
  write_msh(frame_mesh(f), path, batch);
}

FrameSampler::FrameSampler(const Frame& f) : oriented_(f.oriented()), locator_(f.mesh) {
  if (f.num_cells() == 0 || f.num_cells() != f.mesh.num_cells())
    throw InputError("", "FrameSampler: the frame has " + std::to_string(f.num_cells()) + " matrices M for a background of " +
                             std::to_string(f.mesh.num_cells()) + " cells (an empty or default-built Frame? read it "
                             "with read_frame or frame_from_mesh)");
}

std::vector<Mat2> Frame::at_cells(const Mesh& m, int* outside) const {
  const FrameSampler sampler(*this);
  std::vector<Mat2> r(m.num_cells());
  int out = 0;
  for (int c = 0; c < m.num_cells(); ++c) {
    bool inside = true;
    r[c] = sampler.at(cell_centroid(m, c), &inside);
    if (!inside) ++out;
  }
  if (outside) *outside = out;
  return r;
}

int FrameSampler::cell(const Vec2& x, bool* inside) const {
  int c = locator_.locate(x);
  if (inside) *inside = c >= 0;
  if (c < 0) return locator_.locate_or_nearest(x);
  if (locator_.well_inside(c, x)) return c;
  // On an edge or a vertex shared by cells: the finest of them (largest |det M|; equal: the lowest
  // index). The lowest index alone followed the canonical order (x, then y), which a turned or
  // mirrored frame does not share: quadsmooth's wall nodes on a background vertex took another
  // cell's metric in the turned problem (docs/quad-quality.md, "Turned and mirrored graded frames").
  std::vector<int> all;
  locator_.locate_all(x, all);  // ascending, so the first of equally fine cells stays
  double best = 0;
  for (int d : all) {
    const double det = std::abs(oriented_[d].determinant());
    if (det > best) {
      best = det;
      c = d;
    }
  }
  return c;
}

}  // namespace quadapt
