#include "bamg/inria_mesh.hpp"

#include <cmath>
#include <fstream>
#include <iomanip>
#include <sstream>

#include "core/error.hpp"

namespace quadapt {

void write_inria_mesh(const InriaMesh& m, std::ostream& out) {
  out << std::setprecision(17);
  out << "MeshVersionFormatted 1\nDimension 2\n";
  out << "Vertices\n" << m.vertices.size() << "\n";
  for (size_t i = 0; i < m.vertices.size(); ++i)
    out << m.vertices[i].x() << " " << m.vertices[i].y() << " " << (i < m.vertex_ref.size() ? m.vertex_ref[i] : 0)
        << "\n";
  if (!m.edges.empty()) {
    out << "Edges\n" << m.edges.size() << "\n";
    for (const auto& e : m.edges) out << e[0] + 1 << " " << e[1] + 1 << " " << e[2] << "\n";
  }
  if (!m.triangles.empty()) {
    out << "Triangles\n" << m.triangles.size() << "\n";
    for (const auto& t : m.triangles) out << t[0] + 1 << " " << t[1] + 1 << " " << t[2] + 1 << " " << t[3] << "\n";
  }
  if (!m.corners.empty()) {
    out << "Corners\n" << m.corners.size() << "\n";
    for (int v : m.corners) out << v + 1 << "\n";
  }
  if (!m.required_vertices.empty()) {
    out << "RequiredVertices\n" << m.required_vertices.size() << "\n";
    for (int v : m.required_vertices) out << v + 1 << "\n";
  }
  out << "End\n";
  if (!out) throw ExternalError("cannot write an INRIA .mesh file");
}

void write_inria_mesh(const InriaMesh& m, const std::string& path) {
  std::ofstream f(path);
  if (!f) throw ExternalError(path + ": cannot create");
  write_inria_mesh(m, f);
  f.close();
  if (!f) throw ExternalError(path + ": write failed");
}

namespace {
struct Reader {
  std::istream& in;
  const std::string& path;
  std::string tok;
  bool next() {
    while (in >> tok) {
      if (!tok.empty() && tok[0] == '#') {  // comment to end of line
        std::string rest;
        std::getline(in, rest);
        continue;
      }
      return true;
    }
    return false;
  }
  long integer(const char* what) {
    if (!next()) throw InputError(path, std::string("truncated file while reading ") + what);
    char* end = nullptr;
    long v = std::strtol(tok.c_str(), &end, 10);
    if (*end) throw InputError(path, std::string("expected an integer (") + what + "), got '" + tok + "'");
    return v;
  }
  double real(const char* what) {
    if (!next()) throw InputError(path, std::string("truncated file while reading ") + what);
    char* end = nullptr;
    double v = std::strtod(tok.c_str(), &end);
    if (*end || !std::isfinite(v)) throw InputError(path, std::string("expected a finite number (") + what + "), got '" + tok + "'");
    return v;
  }
  long count(const char* what) {
    long n = integer(what);
    if (n < 0 || n > 100000000) throw InputError(path, std::string("bad count for ") + what);
    return n;
  }
};
}  // namespace

InriaMesh read_inria_mesh(std::istream& in, const std::string& path) {
  InriaMesh m;
  Reader r{in, path, {}};
  int dim = 2;
  auto index = [&](long v, const char* what) {
    if (v < 1 || v > static_cast<long>(m.vertices.size()))
      throw InputError(path, std::string(what) + " refers to vertex " + std::to_string(v) + " of " +
                                 std::to_string(m.vertices.size()));
    return static_cast<int>(v - 1);
  };
  bool any = false;
  while (r.next()) {
    const std::string kw = r.tok;
    if (kw == "MeshVersionFormatted") {
      r.integer("version");
      any = true;
    } else if (kw == "Dimension") {
      dim = static_cast<int>(r.integer("dimension"));
      if (dim != 2) throw InputError(path, "only 2D .mesh files are supported (Dimension " + std::to_string(dim) + ")");
    } else if (kw == "Vertices") {
      long n = r.count("Vertices");
      m.vertices.resize(n);
      m.vertex_ref.resize(n);
      for (long i = 0; i < n; ++i) {
        double x = r.real("vertex x"), y = r.real("vertex y");
        m.vertices[i] = Vec2(x, y);
        m.vertex_ref[i] = static_cast<int>(r.integer("vertex ref"));
      }
    } else if (kw == "Edges") {
      long n = r.count("Edges");
      m.edges.resize(n);
      for (long i = 0; i < n; ++i) {
        int a = index(r.integer("edge"), "an edge"), b = index(r.integer("edge"), "an edge");
        m.edges[i] = {a, b, static_cast<int>(r.integer("edge ref"))};
      }
    } else if (kw == "Triangles") {
      long n = r.count("Triangles");
      m.triangles.resize(n);
      for (long i = 0; i < n; ++i) {
        int a = index(r.integer("triangle"), "a triangle"), b = index(r.integer("triangle"), "a triangle"),
            c = index(r.integer("triangle"), "a triangle");
        m.triangles[i] = {a, b, c, static_cast<int>(r.integer("triangle ref"))};
      }
    } else if (kw == "Corners" || kw == "RequiredVertices") {
      long n = r.count(kw.c_str());
      auto& dst = kw == "Corners" ? m.corners : m.required_vertices;
      for (long i = 0; i < n; ++i) dst.push_back(index(r.integer(kw.c_str()), kw.c_str()));
    } else if (kw == "End") {
      break;
    } else if (kw == "Identifier" || kw == "Geometry") {
      std::string rest;  // a quoted string on the next line
      std::getline(in, rest);
      if (rest.find_first_not_of(" \t\r") == std::string::npos) std::getline(in, rest);
    } else if (kw == "Quadrilaterals") {
      long n = r.count("Quadrilaterals");
      if (n > 0) throw InputError(path, "quadrilaterals in a BAMG triangle mesh are not supported");
    } else {
      // A section we do not need: a count followed by records of unknown width. Known BAMG
      // sections have integer/real tokens only; skip tokens until the next keyword.
      while (in >> std::ws && in.peek() != EOF) {
        int ch = in.peek();
        if (std::isalpha(ch)) break;
        r.next();
      }
    }
  }
  if (!any && m.vertices.empty()) throw InputError(path, "not an INRIA .mesh file (no MeshVersionFormatted/Vertices)");
  return m;
}

InriaMesh read_inria_mesh(const std::string& path) {
  std::ifstream f(path);
  if (!f) throw InputError(path, "cannot open");
  return read_inria_mesh(f, path);
}

void write_bamg_metric(const std::vector<Eigen::Matrix2d>& metric, std::ostream& out) {
  out << std::setprecision(17) << metric.size() << " 3\n";
  for (const auto& M : metric) out << M(0, 0) << " " << 0.5 * (M(0, 1) + M(1, 0)) << " " << M(1, 1) << "\n";
  if (!out) throw ExternalError("cannot write a BAMG metric file");
}

void write_bamg_metric(const std::vector<Eigen::Matrix2d>& metric, const std::string& path) {
  std::ofstream f(path);
  if (!f) throw ExternalError(path + ": cannot create");
  write_bamg_metric(metric, f);
  f.close();
  if (!f) throw ExternalError(path + ": write failed");
}

}  // namespace quadapt
