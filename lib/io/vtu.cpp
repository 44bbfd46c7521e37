#include "io/vtu.hpp"

#include <algorithm>
#include <cstdio>
#include <filesystem>
#include <ostream>

#include "core/atomic_file.hpp"
#include "core/error.hpp"
#include "core/file_name.hpp"
#include "fem/basis.hpp"
#include "io/msh.hpp"

namespace quadapt {

int vtk_lagrange_quad_node(int q, int k) {
  const int n = q + 1;
  auto idx = [n](int a, int b) { return a + n * b; };
  static const int corner_a[4] = {0, 1, 1, 0}, corner_b[4] = {0, 0, 1, 1};
  if (k < 4) return idx(corner_a[k] * q, corner_b[k] * q);
  k -= 4;
  const int e = q - 1;  // points per edge
  if (k < e) return idx(1 + k, 0);              // bottom, a increasing
  if (k < 2 * e) return idx(q, 1 + (k - e));    // right, b increasing
  if (k < 3 * e) return idx(1 + (k - 2 * e), q);  // top, a increasing
  if (k < 4 * e) return idx(0, 1 + (k - 3 * e));  // left, b increasing
  k -= 4 * e;
  return idx(1 + k % e, 1 + k / e);             // interior, a fastest
}

namespace {

void put(std::ostream& out, double v) {
  char buf[32];
  std::snprintf(buf, sizeof buf, "%.17g", v);
  out << buf;
}

// Points of one cell: the reference points (xi, eta) where values are written.
struct CellPoints {
  std::vector<double> xi, eta;
};

}  // namespace

void write_vtu(const Mesh& m, std::ostream& out, const std::string& path) {
  int q = 0;  // largest DG degree; 0 = no CellNodeFields
  bool node_fields = !m.cell_node_fields.empty();
  for (const auto& f : m.cell_node_fields) q = std::max(q, std::max(f.degree, 1));
  if (q > 1 && !m.all_quads())
    throw InputError(path, "a DG field (degree " + std::to_string(q) +
                               ") on a mesh with triangles cannot be written as VTK Lagrange quadrilaterals");
  const int nc = m.num_cells();
  // Curved cells (mesh/curved.hpp) are Lagrange quadrilaterals of degree max(p, q) on the map.
  if (m.is_curved()) q = std::max(q, m.geometric_order());
  const bool cell_points = node_fields || m.is_curved();

  // Points and connectivity.
  std::vector<Vec2> pts;
  std::vector<int> conn, offsets, types;
  std::vector<CellPoints> refs;  // per cell, only when node_fields
  if (!cell_points) {
    pts = m.nodes;
    for (int c = 0; c < nc; ++c) {
      for (int i = 0; i < m.cells[c].nv; ++i) conn.push_back(m.cells[c].v[i]);
      offsets.push_back(static_cast<int>(conn.size()));
      types.push_back(m.cells[c].is_quad() ? kVtkQuad : kVtkTriangle);
    }
  } else {
    refs.resize(nc);
    for (int c = 0; c < nc; ++c) {
      CellPoints& r = refs[c];
      if (!m.cells[c].is_quad()) {  // linear triangle, own points (reference (0,0),(1,0),(0,1))
        r.xi = {0, 1, 0};
        r.eta = {0, 0, 1};
        types.push_back(kVtkTriangle);
      } else {
        const int npt = (q + 1) * (q + 1);
        for (int k = 0; k < npt; ++k) {
          const int ab = vtk_lagrange_quad_node(q, k);
          r.xi.push_back(-1.0 + 2.0 * (ab % (q + 1)) / q);
          r.eta.push_back(-1.0 + 2.0 * (ab / (q + 1)) / q);
        }
        types.push_back(q == 1 ? kVtkQuad : kVtkLagrangeQuadrilateral);
      }
      for (size_t k = 0; k < r.xi.size(); ++k) {
        conn.push_back(static_cast<int>(pts.size()));
        pts.push_back(map_to_physical(m, c, r.xi[k], r.eta[k]));
      }
      offsets.push_back(static_cast<int>(conn.size()));
    }
  }

  out << "<?xml version=\"1.0\"?>\n"
         "<VTKFile type=\"UnstructuredGrid\" version=\"1.0\" byte_order=\"LittleEndian\" header_type=\"UInt64\">\n"
         "<UnstructuredGrid>\n"
      << "<Piece NumberOfPoints=\"" << pts.size() << "\" NumberOfCells=\"" << nc << "\">\n";

  // Point data: the CellNodeFields evaluated at each cell's points.
  if (node_fields) {
    out << "<PointData Scalars=\"" << m.cell_node_fields.front().name << "\">\n";
    for (const auto& f : m.cell_node_fields) {
      out << "<DataArray type=\"Float64\" Name=\"" << f.name << "\" NumberOfComponents=\"" << f.ncomp
          << "\" format=\"ascii\">\n";
      const bool dg = f.degree >= 1;
      LagrangeBasis1D basis(dg ? f.degree : 1);
      std::vector<double> comp(static_cast<size_t>(f.per_cell));
      for (int c = 0; c < nc; ++c) {
        const double* v = f.cell(c);
        const CellPoints& r = refs[c];
        const int nv = m.cells[c].nv;
        if (dg && f.per_cell != basis.size() * basis.size())
          throw InputError(path, "field '" + f.name + "' has " + std::to_string(f.per_cell) +
                                     " values per cell, not (p+1)^2 for degree " + std::to_string(f.degree));
        if (!dg && f.per_cell != nv)
          throw InputError(path, "field '" + f.name + "' has " + std::to_string(f.per_cell) +
                                     " values per cell; only vertex values (" + std::to_string(nv) +
                                     ") or a DG field can be written to VTK");
        for (size_t k = 0; k < r.xi.size(); ++k) {
          for (int j = 0; j < f.ncomp; ++j) {
            for (int i = 0; i < f.per_cell; ++i) comp[i] = v[static_cast<size_t>(i) * f.ncomp + j];
            double val;
            const double x = r.xi[k], y = r.eta[k];
            if (dg) {
              val = eval_tensor(basis, comp.data(), x, y);
            } else if (nv == 4) {  // bilinear in the vertex values (Gmsh's vertex order)
              val = 0.25 * ((1 - x) * (1 - y) * comp[0] + (1 + x) * (1 - y) * comp[1] +
                            (1 + x) * (1 + y) * comp[2] + (1 - x) * (1 + y) * comp[3]);
            } else {  // linear on the reference triangle
              val = (1 - x - y) * comp[0] + x * comp[1] + y * comp[2];
            }
            put(out, val);
            out << (j + 1 < f.ncomp ? ' ' : '\n');
          }
        }
      }
      out << "</DataArray>\n";
    }
    out << "</PointData>\n";
  }

  // The first 9-component field (the frame Vinv) is the grid's active tensor (ParaView's
  // Tensor Glyph filter picks it up without a choice).
  out << "<CellData";
  for (const auto& f : m.cell_fields)
    if (f.ncomp == 9) {
      out << " Tensors=\"" << f.name << "\"";
      break;
    }
  out << ">\n<DataArray type=\"Int64\" Name=\"cell\" format=\"ascii\">\n";
  for (int c = 0; c < nc; ++c) out << c + 1 << '\n';
  out << "</DataArray>\n";
  for (const auto& f : m.cell_fields) {
    out << "<DataArray type=\"Float64\" Name=\"" << f.name << "\" NumberOfComponents=\"" << f.ncomp
        << "\" format=\"ascii\">\n";
    for (int c = 0; c < nc; ++c)
      for (int j = 0; j < f.ncomp; ++j) {
        put(out, f(c, j));
        out << (j + 1 < f.ncomp ? ' ' : '\n');
      }
    out << "</DataArray>\n";
  }
  out << "</CellData>\n";

  out << "<Points>\n<DataArray type=\"Float64\" NumberOfComponents=\"3\" format=\"ascii\">\n";
  for (const auto& p : pts) {
    put(out, p.x());
    out << ' ';
    put(out, p.y());
    out << " 0\n";
  }
  out << "</DataArray>\n</Points>\n<Cells>\n<DataArray type=\"Int64\" Name=\"connectivity\" format=\"ascii\">\n";
  for (size_t i = 0; i < conn.size(); ++i) out << conn[i] << (i + 1 == conn.size() || (i + 1) % 16 == 0 ? '\n' : ' ');
  out << "</DataArray>\n<DataArray type=\"Int64\" Name=\"offsets\" format=\"ascii\">\n";
  for (int o : offsets) out << o << '\n';
  out << "</DataArray>\n<DataArray type=\"UInt8\" Name=\"types\" format=\"ascii\">\n";
  for (int t : types) out << t << '\n';
  out << "</DataArray>\n</Cells>\n</Piece>\n</UnstructuredGrid>\n</VTKFile>\n";
}

void write_vtu(const Mesh& mesh, const std::string& path) {
  atomic_write(path, [&](std::ostream& out) { write_vtu(mesh, out, path); });
}

MeshFileFormat mesh_file_format(const std::string& path) {
  const std::string ext = lower_extension(path);
  if (ext == ".vtu") return MeshFileFormat::Vtu;
  if (ext.empty() || ext == ".msh") return MeshFileFormat::Msh;
  throw InputError(path, "a mesh is written as .msh (MSH 4.1) or .vtu (VTK XML for ParaView), not '" + ext + "'");
}

void write_mesh_file(const Mesh& mesh, const std::string& path) {
  if (mesh_file_format(path) == MeshFileFormat::Vtu)
    write_vtu(mesh, path);
  else
    write_msh(mesh, path);
}

}  // namespace quadapt
