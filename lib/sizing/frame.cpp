#include "sizing/frame.hpp"

#include <cmath>

namespace quadapt {

Eigen::Matrix2d frame_inverse(double h, double rho, double theta) {
  const double h1 = h * std::sqrt(rho), h2 = h / std::sqrt(rho);
  const double c = std::cos(theta), s = std::sin(theta);
  Eigen::Matrix2d M;
  M << c / h1, s / h1, -s / h2, c / h2;
  return M;
}

std::array<double, 9> vinv_components(const Eigen::Matrix2d& M) {
  return {{M(0, 0), M(0, 1), 0.0, M(1, 0), M(1, 1), 0.0, 0.0, 0.0, 0.0}};
}

Mesh make_frame_mesh(const Mesh& shape, const SizeResult& r) {
  Mesh m = shape;
  m.clear_fields();
  const int nc = m.num_cells();
  CellField vinv;
  vinv.name = "Vinv";
  vinv.ncomp = 9;
  vinv.values.resize(static_cast<size_t>(nc) * 9);
  for (int k = 0; k < nc; ++k) {
    auto comp = vinv_components(frame_inverse(r.h[k], r.rho[k], r.theta[k]));
    for (int i = 0; i < 9; ++i) vinv(k, i) = comp[i];
  }
  m.set_field(std::move(vinv));
  auto scalar = [&](const std::string& name, const std::vector<double>& v) {
    CellField f;
    f.name = name;
    f.values = v;
    m.set_field(std::move(f));
  };
  scalar("h", r.h);
  scalar("theta", r.theta);
  scalar("rho", r.rho);
  if (!r.alpha.empty()) scalar("alpha", r.alpha);
  return m;
}

}  // namespace quadapt
