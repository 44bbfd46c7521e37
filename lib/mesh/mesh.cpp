#include "mesh/mesh.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <random>

#include "core/error.hpp"
#include "fem/basis.hpp"
#include "mesh/curved.hpp"

namespace quadapt {

int Mesh::num_quads() const {
  return static_cast<int>(std::count_if(cells.begin(), cells.end(), [](const Cell& c) { return c.nv == 4; }));
}
int Mesh::num_triangles() const {
  return static_cast<int>(std::count_if(cells.begin(), cells.end(), [](const Cell& c) { return c.nv == 3; }));
}

int Mesh::find_group(const std::string& name) const {
  for (size_t i = 0; i < groups.size(); ++i)
    if (groups[i].name == name) return static_cast<int>(i);
  return -1;
}

int Mesh::group_index(const std::string& name) {
  int g = find_group(name);
  if (g >= 0) return g;
  // Above the domain's tag, as before (unless a file gave that as INT_MAX).
  const int lowest = domain_tag < std::numeric_limits<int>::max() ? domain_tag + 1 : 1;
  groups.push_back({free_tag(lowest), name});
  return static_cast<int>(groups.size()) - 1;
}

int Mesh::free_tag(int lowest) const {
  int top = 0;
  for (const auto& gr : groups) top = std::max(top, gr.tag);
  if (top < std::numeric_limits<int>::max()) return std::max(lowest, top + 1);
  std::vector<int> used;
  for (const auto& gr : groups) used.push_back(gr.tag);
  std::sort(used.begin(), used.end());
  int t = 1;
  for (int u : used)
    if (u == t) ++t;
    else if (u > t) break;
  return t;
}

const CellField* Mesh::cell_field(const std::string& name) const {
  for (const auto& f : cell_fields)
    if (f.name == name) return &f;
  return nullptr;
}
CellField* Mesh::cell_field(const std::string& name) {
  for (auto& f : cell_fields)
    if (f.name == name) return &f;
  return nullptr;
}
std::string Mesh::field_list() const {
  std::string have;
  for (const auto& f : cell_fields) have += (have.empty() ? "" : ", ") + f.name;
  for (const auto& f : cell_node_fields) have += (have.empty() ? "" : ", ") + f.name + " (node field)";
  return have.empty() ? "none" : have;
}

const CellNodeField* Mesh::cell_node_field(const std::string& name) const {
  for (const auto& f : cell_node_fields)
    if (f.name == name) return &f;
  return nullptr;
}
CellNodeField* Mesh::cell_node_field(const std::string& name) {
  for (auto& f : cell_node_fields)
    if (f.name == name) return &f;
  return nullptr;
}

void Mesh::set_field(CellField f) {
  if (f.ncomp <= 0 || f.values.size() != static_cast<size_t>(num_cells()) * f.ncomp)
    throw Error("field '" + f.name + "' has " + std::to_string(f.values.size()) +
                " values, expected " + std::to_string(num_cells()) + " cells x " + std::to_string(f.ncomp));
  if (auto* old = cell_field(f.name)) *old = std::move(f);
  else cell_fields.push_back(std::move(f));
}

void Mesh::set_field(CellNodeField f) {
  if (f.ncomp <= 0 || f.per_cell <= 0 ||
      f.values.size() != static_cast<size_t>(num_cells()) * f.per_cell * f.ncomp)
    throw Error("field '" + f.name + "' has " + std::to_string(f.values.size()) + " values, expected " +
                std::to_string(num_cells()) + " cells x " + std::to_string(f.per_cell) + " points x " +
                std::to_string(f.ncomp));
  if (auto* old = cell_node_field(f.name)) *old = std::move(f);
  else cell_node_fields.push_back(std::move(f));
}

double cell_area(const Mesh& m, int c) {
  const Cell& cell = m.cells[c];
  if (m.is_curved() && cell.nv == 4) {
    // det J has degree 2q-1 in each variable: q+1 Gauss points are exact.
    static const std::vector<Rule1D> rules = [] {
      std::vector<Rule1D> r(kMaxGeometricOrder + 1);
      for (int q = 2; q <= kMaxGeometricOrder; ++q) r[q] = gauss_legendre(q + 1);
      return r;
    }();
    const Rule1D& rule = rules.at(m.geometric_order());
    const int n = static_cast<int>(rule.x.size());
    const double* x = rule.x.data();
    const double* w = rule.w.data();
    CellMap G(m, c);
    double a = 0;
    Vec2 t1, t2;
    for (int j = 0; j < n; ++j)
      for (int i = 0; i < n; ++i) a += w[i] * w[j] * G.jacobian(x[i], x[j], t1, t2);
    return a;
  }
  // shoelace about the first vertex: on absolute coordinates the sum loses |x|^2 eps, so a unit
  // cell at x = 1e7 had "zero area" (a review, session 35)
  const Vec2& o = m.nodes[cell.v[0]];
  double a = 0;
  for (int i = 1; i + 1 < cell.nv; ++i) {
    const Vec2 p = m.nodes[cell.v[i]] - o;
    const Vec2 q = m.nodes[cell.v[i + 1]] - o;
    a += p.x() * q.y() - q.x() * p.y();
  }
  return 0.5 * a;
}

double total_area(const Mesh& m) {
  double a = 0;
  for (int c = 0; c < m.num_cells(); ++c) a += cell_area(m, c);
  return a;
}

Vec2 cell_centroid(const Mesh& m, int c) {
  const Cell& cell = m.cells[c];
  if (cell.nv == 3) return (m.nodes[cell.v[0]] + m.nodes[cell.v[1]] + m.nodes[cell.v[2]]) / 3.0;
  // Quad: area-weighted centroids of the two triangles (0,1,2) and (0,2,3).
  const Vec2 &a = m.nodes[cell.v[0]], &b = m.nodes[cell.v[1]], &cc = m.nodes[cell.v[2]], &d = m.nodes[cell.v[3]];
  auto tri_area = [](const Vec2& p, const Vec2& q, const Vec2& r) {
    return 0.5 * ((q - p).x() * (r - p).y() - (q - p).y() * (r - p).x());
  };
  double a1 = tri_area(a, b, cc), a2 = tri_area(a, cc, d);
  if (std::abs(a1 + a2) < 1e-300) return (a + b + cc + d) / 4.0;
  return (a1 * (a + b + cc) / 3.0 + a2 * (a + cc + d) / 3.0) / (a1 + a2);
}

Vec2 map_to_physical(const Mesh& m, int c, double xi, double eta) {
  const Cell& cell = m.cells[c];
  if (m.is_curved() && cell.nv == 4) return CellMap(m, c).map(xi, eta);
  if (cell.nv == 3) {
    return m.nodes[cell.v[0]] * (1 - xi - eta) + m.nodes[cell.v[1]] * xi + m.nodes[cell.v[2]] * eta;
  }
  const double n0 = 0.25 * (1 - xi) * (1 - eta), n1 = 0.25 * (1 + xi) * (1 - eta);
  const double n2 = 0.25 * (1 + xi) * (1 + eta), n3 = 0.25 * (1 - xi) * (1 + eta);
  return m.nodes[cell.v[0]] * n0 + m.nodes[cell.v[1]] * n1 + m.nodes[cell.v[2]] * n2 + m.nodes[cell.v[3]] * n3;
}

Eigen::Matrix2d map_jacobian(const Mesh& m, int c, double xi, double eta) {
  const Cell& cell = m.cells[c];
  Eigen::Matrix2d J;
  if (m.is_curved() && cell.nv == 4) {
    Vec2 t1, t2;
    CellMap(m, c).jacobian(xi, eta, t1, t2);
    J.col(0) = t1;
    J.col(1) = t2;
    return J;
  }
  if (cell.nv == 3) {
    J.col(0) = m.nodes[cell.v[1]] - m.nodes[cell.v[0]];
    J.col(1) = m.nodes[cell.v[2]] - m.nodes[cell.v[0]];
    return J;
  }
  const Vec2 &p0 = m.nodes[cell.v[0]], &p1 = m.nodes[cell.v[1]], &p2 = m.nodes[cell.v[2]], &p3 = m.nodes[cell.v[3]];
  J.col(0) = 0.25 * ((p1 - p0) * (1 - eta) + (p2 - p3) * (1 + eta));
  J.col(1) = 0.25 * ((p3 - p0) * (1 - xi) + (p2 - p1) * (1 + xi));
  return J;
}

double cell_size(const Mesh& m, int c) { return std::sqrt(std::abs(cell_area(m, c))); }

double segment_distance(const Vec2& p, const Vec2& a, const Vec2& b) {
  const Vec2 d = b - a;
  const double l2 = d.squaredNorm();
  const double t = l2 > 0 ? std::clamp((p - a).dot(d) / l2, 0.0, 1.0) : 0.0;
  return (p - (a + t * d)).norm();
}

Mesh make_structured_quads(int nx, int ny, double x0, double x1, double y0, double y1) {
  if (nx < 1 || ny < 1) throw Error("structured grid needs at least 1x1 cells");
  Mesh m;
  m.nodes.resize(static_cast<size_t>(nx + 1) * (ny + 1));
  auto id = [nx](int i, int j) { return j * (nx + 1) + i; };
  for (int j = 0; j <= ny; ++j)
    for (int i = 0; i <= nx; ++i) {
      double x = (i == nx) ? x1 : x0 + (x1 - x0) * i / nx;
      double y = (j == ny) ? y1 : y0 + (y1 - y0) * j / ny;
      m.nodes[id(i, j)] = Vec2(x, y);
    }
  for (int j = 0; j < ny; ++j)
    for (int i = 0; i < nx; ++i) {
      Cell c;
      c.nv = 4;
      c.v = {id(i, j), id(i + 1, j), id(i + 1, j + 1), id(i, j + 1)};
      m.cells.push_back(c);
    }
  m.groups = {{1, "bottom"}, {2, "right"}, {3, "top"}, {4, "left"}};
  m.domain_tag = 5;
  for (int i = 0; i < nx; ++i) m.boundary.push_back({{id(i, 0), id(i + 1, 0)}, 0});
  for (int j = 0; j < ny; ++j) m.boundary.push_back({{id(nx, j), id(nx, j + 1)}, 1});
  for (int i = nx; i > 0; --i) m.boundary.push_back({{id(i, ny), id(i - 1, ny)}, 2});
  for (int j = ny; j > 0; --j) m.boundary.push_back({{id(0, j), id(0, j - 1)}, 3});
  return m;
}

Mesh make_perturbed_quads(int nx, int ny, double amplitude, unsigned seed) {
  Mesh m = make_structured_quads(nx, ny);
  std::mt19937 rng(seed);
  std::uniform_real_distribution<double> u(-amplitude, amplitude);
  const double hx = 1.0 / nx, hy = 1.0 / ny;
  for (int j = 1; j < ny; ++j)
    for (int i = 1; i < nx; ++i) {
      Vec2& p = m.nodes[j * (nx + 1) + i];
      p.x() += u(rng) * hx;
      p.y() += u(rng) * hy;
    }
  return m;
}

}  // namespace quadapt
