// fit_frame (lib/lpcvt/fit_frame.hpp): the frame quadsmooth's shape fit aims at.
#include <doctest/doctest.h>

#include <Eigen/Eigenvalues>
#include <cmath>

#include "core/error.hpp"
#include "frame/frame.hpp"
#include "lpcvt/fit_frame.hpp"
#include "mesh/mesh.hpp"

using quadapt::Frame;
using quadapt::Mat2;
using namespace quadapt::lpcvt;

namespace {

/// An n x n grid on the unit square with frame_inverse(h, rho, theta) per cell; `hot` cells
/// (centroid within 0.06 of (0.5, 0.5)) get size h / 5.
Frame grid_frame(int n, double h, double rho, double theta, bool hot) {
  Frame f;
  f.mesh = quadapt::make_structured_quads(n, n);
  f.M.resize(f.mesh.num_cells());
  for (int c = 0; c < f.mesh.num_cells(); ++c) {
    const quadapt::Vec2 g = quadapt::cell_centroid(f.mesh, c);
    const bool fine = hot && (g - quadapt::Vec2(0.5, 0.5)).norm() < 0.06;
    f.M[c] = quadapt::frame_inverse(fine ? h / 5 : h, rho, theta);
  }
  return f;
}

double density(const Mat2& M) { return std::abs(M.determinant()); }

/// The smallest eigenvalue of A^T A - B^T B, relative to |B^T B|: >= 0 when A is nowhere coarser than B.
double containment(const Mat2& A, const Mat2& B) {
  const Mat2 D = A.transpose() * A - B.transpose() * B;
  Eigen::SelfAdjointEigenSolver<Mat2> es(0.5 * (D + D.transpose()));
  return es.eigenvalues()[0] / (B.transpose() * B).norm();
}

}  // namespace

TEST_CASE("fit_frame: a constant frame is the raw frame bit for bit in every mode") {
  const Frame raw = grid_frame(8, 0.03, 4, 0.6, false);
  for (FitFrame mode : {FitFrame::Raw, FitFrame::Meshed, FitFrame::Capped}) {
    FitFrameOptions o;
    o.mode = mode;
    const Frame f = fit_frame(raw, o);
    CAPTURE(to_string(mode));
    REQUIRE(f.num_cells() == raw.num_cells());
    for (int c = 0; c < raw.num_cells(); ++c) CHECK(f.M[c] == raw.M[c]);
  }
}

TEST_CASE("fit_frame: meshed smooths an isolated fine cell away, capped keeps it and the meshed cell count") {
  const Frame raw = grid_frame(9, 0.04, 3, 0.4, true);  // one hot cell, the centre one
  FitFrameOptions om, oc;
  om.mode = FitFrame::Meshed;
  oc.mode = FitFrame::Capped;
  FitFrameReport rc;
  const Frame meshed = fit_frame(raw, om), capped = fit_frame(raw, oc, &rc);
  int hot = -1;
  for (int c = 0; c < raw.num_cells(); ++c)
    if (density(raw.M[c]) > density(raw.M[0]) * 2) hot = c;
  REQUIRE(hot >= 0);
  MESSAGE("hot cell density raw " << density(raw.M[hot]) << ", meshed " << density(meshed.M[hot]) << ", capped "
                                  << density(capped.M[hot]) << "; cap rescale " << rc.cap_rescale << ", capped cells "
                                  << rc.capped_cells);
  // the smoothing dilutes the 25x denser cell
  CHECK(density(meshed.M[hot]) < 0.3 * density(raw.M[hot]));
  // capped: nowhere coarser than the raw frame, up to the uniform rescale s (sizes / s)
  const double s = rc.cap_rescale;
  CHECK(s < 1);
  CHECK(rc.capped_cells > 0);
  for (int c = 0; c < raw.num_cells(); ++c) {
    CAPTURE(c);
    CHECK(containment(capped.M[c], s * raw.M[c]) > -1e-9);
    CHECK(containment(capped.M[c], s * meshed.M[c]) > -1e-9);
  }
  CHECK(density(capped.M[hot]) >= s * s * density(raw.M[hot]) * (1 - 1e-9));
  // the cells it asks: the meshed frame's (lpcvt's point count)
  CHECK(capped.target_cells() == doctest::Approx(meshed.target_cells()).epsilon(1e-12));
  CHECK(meshed.target_cells() == doctest::Approx(raw.target_cells()).epsilon(1e-12));
}

TEST_CASE("fit_frame: words and bad options") {
  CHECK(parse_fit_frame("capped") == FitFrame::Capped);
  CHECK(std::string(to_string(FitFrame::Meshed)) == "meshed");
  CHECK_THROWS_AS(parse_fit_frame("smooth", "x"), quadapt::InputError);
  FitFrameOptions o;
  o.mode = FitFrame::Meshed;
  o.gradation = 0.5;
  CHECK_THROWS_AS(fit_frame(grid_frame(2, 0.1, 1, 0, false), o), quadapt::InputError);
}
