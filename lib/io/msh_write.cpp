// write_msh: Mesh -> Gmsh MSH 4.1 ASCII (see io/msh.hpp for the contract).
//
// Layout: $MeshFormat, $PhysicalNames (boundary groups, then the domain), $Entities (one curve
// per run of consecutive boundary edges of one group, one surface), $Nodes (one block on the
// surface, tags 1..N), $Elements (line blocks, tags C+1..C+E; cell blocks per run of one type,
// tags 1..C so that cell i is element i+1), $InterpolationScheme per DG degree, then one
// $ElementData / $ElementNodeData view per field. Numbers: shortest decimal form that reads
// back to the same double (std::to_chars; at most 17 significant digits).
#include <algorithm>
#include <charconv>
#include <cmath>
#include <ostream>
#include <map>
#include <set>
#include <string>
#include <unordered_map>

#include "core/atomic_file.hpp"
#include "io/gmsh_options.hpp"
#include "core/error.hpp"
#include "io/gll_scheme.hpp"
#include "io/msh.hpp"
#include "mesh/curved.hpp"

namespace quadapt {

namespace {

class Out {
 public:
  explicit Out(std::ostream& os) : os_(os) { buf_.reserve(1 << 16); }
  ~Out() { flush(); }
  Out& operator<<(double v) {
    char tmp[32];
    auto r = std::to_chars(tmp, tmp + sizeof(tmp), v);
    buf_.append(tmp, r.ptr);
    return maybe_flush();
  }
  Out& operator<<(long long v) {
    char tmp[24];
    auto r = std::to_chars(tmp, tmp + sizeof(tmp), v);
    buf_.append(tmp, r.ptr);
    return maybe_flush();
  }
  Out& operator<<(int v) { return *this << static_cast<long long>(v); }
  Out& operator<<(size_t v) { return *this << static_cast<long long>(v); }
  Out& operator<<(const std::string& s) {
    buf_ += s;
    return maybe_flush();
  }
  Out& operator<<(const char* s) {
    buf_ += s;
    return maybe_flush();
  }
  Out& operator<<(char c) {
    buf_ += c;
    return maybe_flush();
  }
  void flush() {
    os_.write(buf_.data(), static_cast<std::streamsize>(buf_.size()));
    buf_.clear();
  }

 private:
  Out& maybe_flush() {
    if (buf_.size() > (1 << 16)) flush();
    return *this;
  }
  std::ostream& os_;
  std::string buf_;
};

std::string quote(const std::string& s) {
  std::string q = s;
  std::replace(q.begin(), q.end(), '"', '\'');
  std::replace(q.begin(), q.end(), '\n', ' ');
  return "\"" + q + "\"";
}

struct Run {
  int begin, end;  // [begin, end) indices
  int key;         // group (edges) or nv (cells)
};

template <class F>
std::vector<Run> runs(int n, F key) {
  std::vector<Run> r;
  for (int i = 0; i < n; ++i) {
    int k = key(i);
    if (r.empty() || r.back().key != k) r.push_back({i, i + 1, k});
    else r.back().end = i + 1;
  }
  return r;
}

// The first cell (1-based, as in the file) whose `per_cell` values hold a NaN or infinity, or 0.
size_t first_non_finite(const std::vector<double>& v, size_t per_cell) {
  for (size_t i = 0; i < v.size(); ++i)
    if (!std::isfinite(v[i])) return i / per_cell + 1;
  return 0;
}

void check_writable(const Mesh& m, const std::string& path) {
  // A result that is not a number is never written as if it were one (exit 2 naming the file).
  for (int i = 0; i < m.num_nodes(); ++i)
    if (!m.nodes[i].allFinite())
      throw NumericalError(path + ": refusing to write a non-finite coordinate (node " + std::to_string(i + 1) + ")");
  for (const CellField& f : m.cell_fields)
    if (size_t c = first_non_finite(f.values, std::max(f.ncomp, 1)))
      throw NumericalError(path + ": refusing to write field '" + f.name + "': not finite in cell " + std::to_string(c));
  for (const CellNodeField& f : m.cell_node_fields)
    if (size_t c = first_non_finite(f.values, std::max(f.per_cell * f.ncomp, 1)))
      throw NumericalError(path + ": refusing to write field '" + f.name + "': not finite in cell " + std::to_string(c));
  for (const Cell& c : m.cells) {
    if (c.nv != 3 && c.nv != 4) throw Error("write_msh: a cell has " + std::to_string(c.nv) + " vertices");
    for (int i = 0; i < c.nv; ++i)
      if (c.v[i] < 0 || c.v[i] >= m.num_nodes()) throw Error("write_msh: a cell refers to a missing node");
  }
  for (const BoundaryEdge& e : m.boundary) {
    if (e.group < 0 || e.group >= static_cast<int>(m.groups.size()))
      throw Error("write_msh: a boundary edge has no group");
    for (int v : e.v)
      if (v < 0 || v >= m.num_nodes()) throw Error("write_msh: a boundary edge refers to a missing node");
  }
  for (const CellField& f : m.cell_fields)
    if (f.ncomp < 1 || f.values.size() != static_cast<size_t>(m.num_cells()) * f.ncomp)
      throw Error("write_msh: field '" + f.name + "' does not match the cell count");
  if (m.is_curved()) {
    if (gmsh_quad_type(m.geometric_order()) < 0 || !m.all_quads())
      throw Error("write_msh: curved meshes of order " + std::to_string(m.geometric_order()) + " with triangles or q > " + std::to_string(kMaxGeometricOrder));
    if (m.curved.points.size() != static_cast<size_t>(m.num_cells()) * m.curved.per_cell())
      throw Error("write_msh: curved control points do not match the cell count");
  }
  for (const CellNodeField& f : m.cell_node_fields) {
    if (f.ncomp < 1 || f.per_cell < 1 || f.values.size() != static_cast<size_t>(m.num_cells()) * f.per_cell * f.ncomp)
      throw Error("write_msh: field '" + f.name + "' does not match the cell count");
    if (f.degree >= 0 && f.per_cell != (f.degree + 1) * (f.degree + 1))
      throw Error("write_msh: field '" + f.name + "' of degree " + std::to_string(f.degree) + " has " +
                  std::to_string(f.per_cell) + " values per cell");
  }
}

/// Node numbering of a curved mesh: the vertices are nodes 1..N; every other control point
/// gets the next number at its first occurrence (cells in order, points in Gmsh order), points
/// with bit-identical coordinates sharing one node. cell_nodes[c] lists the (q+1)^2 node
/// numbers of cell c in Gmsh order, edge_nodes maps a boundary edge to its q+1 node numbers.
struct CurvedNumbering {
  std::vector<Vec2> extra;                   // nodes N+1, N+2, ...
  std::vector<std::vector<long long>> cell_nodes;
  std::vector<std::vector<long long>> boundary_nodes;  // per Mesh::boundary edge, Gmsh line order
};

CurvedNumbering number_curved(const Mesh& m) {
  CurvedNumbering r;
  const int q = m.geometric_order(), n1 = q + 1, nn = m.num_nodes();
  const std::vector<int> perm = gmsh_quad_node_order(q);
  std::map<std::pair<double, double>, long long> at;
  std::map<std::pair<int, int>, std::pair<int, int>> edge_of;  // (v0, v1) oriented -> (cell, edge)
  r.cell_nodes.resize(m.num_cells());
  for (int c = 0; c < m.num_cells(); ++c) {
    const Vec2* X = m.cell_points(c);
    std::vector<long long> lex(n1 * n1, -1);
    lex[0] = m.cells[c].v[0] + 1;
    lex[q] = m.cells[c].v[1] + 1;
    lex[q + n1 * q] = m.cells[c].v[2] + 1;
    lex[n1 * q] = m.cells[c].v[3] + 1;
    for (int k = 0; k < n1 * n1; ++k) {
      if (lex[k] > 0) continue;
      auto [it, fresh] = at.emplace(std::make_pair(X[k].x(), X[k].y()), nn + static_cast<long long>(r.extra.size()) + 1);
      if (fresh) r.extra.push_back(X[k]);
      lex[k] = it->second;
    }
    for (int k : perm) r.cell_nodes[c].push_back(lex[k]);
    for (int e = 0; e < 4; ++e) edge_of[{m.cells[c].v[e], m.cells[c].v[(e + 1) % 4]}] = {c, e};
  }
  for (const BoundaryEdge& be : m.boundary) {
    auto it = edge_of.find({be.v[0], be.v[1]});
    bool reversed = false;
    if (it == edge_of.end()) {
      it = edge_of.find({be.v[1], be.v[0]});
      reversed = true;
    }
    if (it == edge_of.end()) throw Error("write_msh: a boundary edge of a curved mesh is not an edge of a cell");
    const auto [c, e] = it->second;
    std::vector<int> ed = edge_control_points(q, e);
    if (reversed) std::reverse(ed.begin(), ed.end());
    std::vector<long long> lex(n1 * n1);
    for (size_t k = 0; k < perm.size(); ++k) lex[perm[k]] = r.cell_nodes[c][k];
    std::vector<long long> line = {lex[ed[0]], lex[ed[q]]};
    for (int k = 1; k < q; ++k) line.push_back(lex[ed[k]]);
    r.boundary_nodes.push_back(std::move(line));
  }
  return r;
}

void write_view_header(Out& o, const std::string& name, const std::string& scheme, int ncomp, int ncells) {
  o << (scheme.empty() ? "1\n" : "2\n") << quote(name) << '\n';
  if (!scheme.empty()) o << quote(scheme) << '\n';
  o << "1\n0\n3\n0\n" << ncomp << '\n' << ncells << '\n';
}

}  // namespace

void write_msh(const Mesh& m, std::ostream& os) {
  check_writable(m, "write_msh");
  Out o(os);
  const int nc = m.num_cells(), ne = static_cast<int>(m.boundary.size());
  const int q = m.geometric_order();
  const CurvedNumbering cn = q > 1 ? number_curved(m) : CurvedNumbering{};
  const int nn = m.num_nodes() + static_cast<int>(cn.extra.size());
  auto node_at = [&](int i) -> const Vec2& { return i < m.num_nodes() ? m.nodes[i] : cn.extra[i - m.num_nodes()]; };
  o << "$MeshFormat\n4.1 0 8\n$EndMeshFormat\n";

  o << "$PhysicalNames\n" << static_cast<int>(m.groups.size()) + 1 << '\n';
  for (const BoundaryGroup& g : m.groups) o << "1 " << g.tag << ' ' << quote(g.name) << '\n';
  o << "2 " << m.domain_tag << ' ' << quote(m.domain_name) << '\n';
  o << "$EndPhysicalNames\n";

  const std::vector<Run> curves = runs(ne, [&](int i) { return m.boundary[i].group; });
  auto bbox = [&](auto&& nodes_of, int b, int e, double box[4]) {
    box[0] = box[1] = INFINITY;
    box[2] = box[3] = -INFINITY;
    for (int i = b; i < e; ++i)
      for (int v : nodes_of(i)) {
        box[0] = std::min(box[0], node_at(v).x());
        box[1] = std::min(box[1], node_at(v).y());
        box[2] = std::max(box[2], node_at(v).x());
        box[3] = std::max(box[3], node_at(v).y());
      }
    if (b >= e) box[0] = box[1] = box[2] = box[3] = 0;
  };
  o << "$Entities\n0 " << curves.size() << " 1 0\n";
  double box[4];
  for (size_t k = 0; k < curves.size(); ++k) {
    bbox([&](int i) { return std::vector<int>{m.boundary[i].v[0], m.boundary[i].v[1]}; }, curves[k].begin, curves[k].end, box);
    o << static_cast<int>(k) + 1 << ' ' << box[0] << ' ' << box[1] << " 0 " << box[2] << ' ' << box[3] << " 0 1 "
      << m.groups[curves[k].key].tag << " 0\n";
  }
  if (nn > 0) {
    bbox([&](int i) { return std::vector<int>{i}; }, 0, nn, box);
  } else {
    box[0] = box[1] = box[2] = box[3] = 0;
  }
  o << "1 " << box[0] << ' ' << box[1] << " 0 " << box[2] << ' ' << box[3] << " 0 1 " << m.domain_tag << ' '
    << curves.size();
  for (size_t k = 0; k < curves.size(); ++k) o << ' ' << static_cast<int>(k) + 1;
  o << "\n$EndEntities\n";

  o << "$Nodes\n1 " << nn << " 1 " << nn << "\n2 1 0 " << nn << '\n';
  for (int i = 1; i <= nn; ++i) o << i << '\n';
  for (const Vec2& p : m.nodes) o << p.x() << ' ' << p.y() << " 0\n";
  for (const Vec2& p : cn.extra) o << p.x() << ' ' << p.y() << " 0\n";
  o << "$EndNodes\n";

  const std::vector<Run> blocks = runs(nc, [&](int i) { return m.cells[i].nv; });
  o << "$Elements\n" << curves.size() + blocks.size() << ' ' << nc + ne << ' ' << (nc + ne > 0 ? 1 : 0) << ' '
    << nc + ne << '\n';
  for (size_t k = 0; k < curves.size(); ++k) {
    o << "1 " << static_cast<int>(k) + 1 << ' ' << gmsh_line_type(q) << ' ' << curves[k].end - curves[k].begin << '\n';
    for (int i = curves[k].begin; i < curves[k].end; ++i) {
      o << nc + i + 1;
      if (q > 1) {
        for (long long v : cn.boundary_nodes[i]) o << ' ' << v;
      } else {
        o << ' ' << m.boundary[i].v[0] + 1 << ' ' << m.boundary[i].v[1] + 1;
      }
      o << '\n';
    }
  }
  for (const Run& b : blocks) {
    o << "2 1 " << (b.key == 3 ? 2 : gmsh_quad_type(q)) << ' ' << b.end - b.begin << '\n';
    for (int c = b.begin; c < b.end; ++c) {
      o << c + 1;
      if (q > 1) {
        for (long long v : cn.cell_nodes[c]) o << ' ' << v;
      } else {
        for (int i = 0; i < b.key; ++i) o << ' ' << m.cells[c].v[i] + 1;
      }
      o << '\n';
    }
  }
  o << "$EndElements\n";

  std::set<int> degrees;
  for (const CellNodeField& f : m.cell_node_fields)
    if (f.degree >= 0) degrees.insert(f.degree);
  for (int p : degrees) {
    const GmshInterpolation g = gll_interpolation(p);
    o << "$InterpolationScheme\n" << quote(gll_scheme_name(p)) << "\n1\n" << kGmshFamilyQuadrangle << "\n2\n";
    o << g.n << ' ' << g.n << '\n';
    for (int k = 0; k < g.n; ++k) {
      for (int j = 0; j < g.n; ++j) o << (j ? " " : "") << g.coef[static_cast<size_t>(k) * g.n + j];
      o << '\n';
    }
    o << g.n << " 3\n";
    for (int k = 0; k < g.n; ++k) o << g.exp[3 * k] << ' ' << g.exp[3 * k + 1] << ' ' << g.exp[3 * k + 2] << '\n';
    o << "$EndInterpolationScheme\n";
  }

  for (const CellField& f : m.cell_fields) {
    o << "$ElementData\n";
    write_view_header(o, f.name, "", f.ncomp, nc);
    for (int c = 0; c < nc; ++c) {
      o << c + 1;
      for (int k = 0; k < f.ncomp; ++k) o << ' ' << f(c, k);
      o << '\n';
    }
    o << "$EndElementData\n";
  }
  for (const CellNodeField& f : m.cell_node_fields) {
    o << "$ElementNodeData\n";
    write_view_header(o, f.name, f.degree >= 0 ? gll_scheme_name(f.degree) : "", f.ncomp, nc);
    const int len = f.per_cell * f.ncomp;
    for (int c = 0; c < nc; ++c) {
      o << c + 1 << ' ' << f.per_cell;
      const double* v = f.cell(c);
      for (int k = 0; k < len; ++k) o << ' ' << v[k];
      o << '\n';
    }
    o << "$EndElementNodeData\n";
  }
  // Gmsh and other readers skip sections they do not know (MSH 4.1 format description).
  if (!m.frame_convention.empty()) o << "$FrameConvention\n" << m.frame_convention << "\n$EndFrameConvention\n";
  if (!m.solved_case.empty()) o << "$SolvedCase\n" << m.solved_case << "\n$EndSolvedCase\n";
  o.flush();
}

void write_msh(const Mesh& mesh, const std::string& path, OutputBatch& batch) {
  check_writable(mesh, path);
  batch.add(path, [&](std::ostream& os) { write_msh(mesh, os); });
  stage_gmsh_options(mesh, path, batch);
}

void write_msh(const Mesh& mesh, const std::string& path) {
  OutputBatch batch;
  write_msh(mesh, path, batch);
  batch.commit();
}

}  // namespace quadapt
