#include "mesh/label.hpp"

#include <sstream>

namespace quadapt {

std::string number_text(long long i) { return std::to_string(i + 1); }

std::string point_text(const Vec2& p) {
  std::ostringstream s;
  s << "(" << p.x() << ", " << p.y() << ")";
  return s.str();
}

std::string cell_label(const Mesh& m, int c) {
  return "cell " + number_text(c) + " (centroid " + point_text(cell_centroid(m, c)) + ")";
}

}  // namespace quadapt
