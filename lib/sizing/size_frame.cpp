#include "sizing/size_frame.hpp"

#include "frame/frame.hpp"

namespace quadapt {

Mesh make_frame_mesh(const Mesh& shape, const SizeResult& r) {
  Mesh m = shape;
  m.clear_fields();
  std::vector<Mat2> M(m.num_cells());
  for (int k = 0; k < m.num_cells(); ++k) M[k] = frame_inverse(r.h[k], r.rho[k], r.theta[k]);
  set_frame_field(m, M);
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
