// Gmsh itself opens what write_msh writes and sees every field with its values; the DG field
// is interpolated by Gmsh exactly as our basis does (probe). Gmsh-written binary and MSH 2.2
// files read back to the same mesh.
#include <doctest/doctest.h>
#include <gmsh.h>
#include <unistd.h>

#include <cmath>
#include <filesystem>
#include <map>
#include <random>

#include "core/error.hpp"
#include "fem/basis.hpp"
#include "gmsh/session.hpp"
#include "io/msh.hpp"
#include "mesh_compare.hpp"
#include "../worst.hpp"

using namespace quadapt;
namespace fs = std::filesystem;

namespace {

fs::path temp_file(const std::string& stem) {
  return fs::temp_directory_path() / ("quadapt_" + stem + "_" + std::to_string(::getpid()) + ".msh");
}

Mesh fields_mesh() {
  Mesh m = make_perturbed_quads(4, 3, 0.25, 3);
  std::mt19937 rng(11);
  std::uniform_real_distribution<double> u(-2, 2);
  CellField h{"h", 1, {}}, vinv{"Vinv", 9, {}};
  for (int c = 0; c < m.num_cells(); ++c) {
    h.values.push_back(u(rng) / 3);
    for (double v : {u(rng), u(rng), 0.0, u(rng), u(rng), 0.0, 0.0, 0.0, 0.0}) vinv.values.push_back(v);
  }
  m.set_field(h);
  m.set_field(vinv);
  for (int p : {2, 3}) {
    CellNodeField f{"u" + std::to_string(p), 1, (p + 1) * (p + 1), p, {}};
    for (int i = 0; i < m.num_cells() * f.per_cell; ++i) f.values.push_back(u(rng));
    m.set_field(f);
  }
  CellNodeField corners{"corners", 1, 4, -1, {}};
  for (int i = 0; i < m.num_cells() * 4; ++i) corners.values.push_back(u(rng));
  m.set_field(corners);
  return m;
}

std::map<std::string, int> views_by_name() {
  std::vector<int> tags;
  gmsh::view::getTags(tags);
  std::map<std::string, int> out;
  for (int t : tags) {
    std::string name;
    gmsh::option::getString("View[" + std::to_string(gmsh::view::getIndex(t)) + "].Name", name);
    out[name] = t;
  }
  return out;
}

}  // namespace

TEST_CASE("Gmsh opens the written file and shows every field with our values") {
  Mesh m = fields_mesh();
  const fs::path file = temp_file("gmsh_views");
  write_msh(m, file.string());
  GmshSession session;
  gmsh_call("open", [&] { gmsh::open(file.string()); });
  std::map<std::string, int> views = views_by_name();
  REQUIRE(views.size() == 5);

  for (const CellField& f : m.cell_fields) {
    CAPTURE(f.name);
    REQUIRE(views.count(f.name));
    std::string type;
    std::vector<std::size_t> tags;
    std::vector<double> data;
    double time;
    int ncomp;
    gmsh::view::getHomogeneousModelData(views[f.name], 0, type, tags, data, time, ncomp);
    CHECK(type == "ElementData");
    CHECK(ncomp == f.ncomp);
    REQUIRE(tags.size() == static_cast<size_t>(m.num_cells()));
    for (size_t i = 0; i < tags.size(); ++i)
      for (int k = 0; k < ncomp; ++k) CHECK(data[i * ncomp + k] == f(static_cast<int>(tags[i]) - 1, k));
  }
  for (const CellNodeField& f : m.cell_node_fields) {
    CAPTURE(f.name);
    REQUIRE(views.count(f.name));
    std::string type;
    std::vector<std::size_t> tags;
    std::vector<std::vector<double>> data;
    double time;
    int ncomp;
    gmsh::view::getModelData(views[f.name], 0, type, tags, data, time, ncomp);
    CHECK(type == "ElementNodeData");
    REQUIRE(tags.size() == static_cast<size_t>(m.num_cells()));
    for (size_t i = 0; i < tags.size(); ++i) {
      const double* v = f.cell(static_cast<int>(tags[i]) - 1);
      REQUIRE(data[i].size() == static_cast<size_t>(f.per_cell));
      for (int k = 0; k < f.per_cell; ++k) CHECK(data[i][k] == v[k]);
    }
  }

  // Gmsh displays the DG field through our $InterpolationScheme on its adapted visualisation
  // grid (View.AdaptVisualizationGrid). Its Probe plugin reads that grid: at the grid's
  // vertices (reference coordinates on a 2^-3 lattice) it must give our basis's values.
  for (int p : {2, 3}) {
    const CellNodeField& f = *m.cell_node_field("u" + std::to_string(p));
    const int index = gmsh::view::getIndex(views[f.name]);
    const std::string opt = "View[" + std::to_string(index) + "].";
    gmsh_call("adapt", [&] {
      gmsh::option::setNumber(opt + "MaxRecursionLevel", 3);
      gmsh::option::setNumber(opt + "TargetError", -1);
      gmsh::option::setNumber(opt + "AdaptVisualizationGrid", 1);
    });
    LagrangeBasis1D basis(p);
    double worst = 0, scale = 0;
    int probes = 0;
    for (int c = 0; c < m.num_cells(); ++c)
      for (auto [xi, eta] : {std::pair{-0.5, 0.25}, {0.75, -0.25}, {0.25, 0.75}}) {
        Vec2 x = map_to_physical(m, c, xi, eta);
        double value = NAN;
        gmsh_call("probe", [&] {
          gmsh::plugin::setNumber("Probe", "X", x.x());
          gmsh::plugin::setNumber("Probe", "Y", x.y());
          gmsh::plugin::setNumber("Probe", "Z", 0);
          gmsh::plugin::setNumber("Probe", "View", index);
          gmsh::plugin::run("Probe");
          std::vector<int> tags;
          gmsh::view::getTags(tags);
          std::vector<std::string> types;
          std::vector<int> counts;
          std::vector<std::vector<double>> data;
          gmsh::view::getListData(tags.back(), types, counts, data);
          for (size_t k = 0; k < types.size(); ++k)
            if (types[k] == "SP" && counts[k] == 1) value = data[k].back();
          gmsh::view::remove(tags.back());
        });
        const double ours = eval_tensor(basis, f.cell(c), xi, eta);
        worst = quadapt_test::worst_of(worst, std::abs(value - ours));
        scale = std::max(scale, std::abs(ours));
        ++probes;
      }
    CAPTURE(p);
    CHECK(probes == 3 * m.num_cells());
    CHECK(scale > 0.5);
    CHECK(worst < 1e-12);  // NaN (point not found) fails too
  }
  fs::remove(file);
  fs::remove(file.string() + ".opt");  // write_msh's Gmsh display options beside it
}

TEST_CASE("Gmsh-written binary 4.1, ASCII 2.2 and binary 2.2 files read back to the same mesh") {
  Mesh m = fields_mesh();
  const fs::path ours = temp_file("ours");
  write_msh(m, ours.string());
  GmshSession session;
  gmsh_call("open", [&] { gmsh::open(ours.string()); });
  std::map<std::string, int> views = views_by_name();
  struct Variant {
    double version;
    int binary;
  };
  for (Variant var : {Variant{4.1, 1}, Variant{2.2, 0}, Variant{2.2, 1}}) {
    CAPTURE(var.version);
    CAPTURE(var.binary);
    const fs::path out = temp_file("gmsh_written");
    gmsh_call("write", [&] {
      gmsh::option::setNumber("Mesh.MshFileVersion", var.version);
      gmsh::option::setNumber("Mesh.Binary", var.binary);
      gmsh::option::setNumber("PostProcessing.SaveMesh", 0);
      gmsh::write(out.string());
      for (const auto& [name, tag] : views) gmsh::view::write(tag, out.string(), true);
    });
    Mesh r = read_msh(out.string());
    fs::remove(out);
    REQUIRE(r.num_nodes() == m.num_nodes());
    REQUIRE(r.num_cells() == m.num_cells());
    // Gmsh prints %.16g in ASCII (not always exact); binary is exact.
    const double tol = var.binary ? 0.0 : 1e-15;
    for (int i = 0; i < m.num_nodes(); ++i) CHECK((r.nodes[i] - m.nodes[i]).norm() <= tol);
    for (int c = 0; c < m.num_cells(); ++c) CHECK(r.cells[c].v == m.cells[c].v);
    REQUIRE(r.groups.size() == m.groups.size());
    for (size_t g = 0; g < m.groups.size(); ++g) CHECK(r.groups[g].name == m.groups[g].name);
    REQUIRE(r.boundary.size() == m.boundary.size());
    for (size_t e = 0; e < m.boundary.size(); ++e) CHECK(r.boundary[e].v == m.boundary[e].v);
    CHECK(r.domain_name == m.domain_name);
    for (const CellField& f : m.cell_fields) {
      const CellField* g = r.cell_field(f.name);
      REQUIRE(g);
      REQUIRE(g->values.size() == f.values.size());
      for (size_t i = 0; i < f.values.size(); ++i) CHECK(std::abs(g->values[i] - f.values[i]) <= 4 * tol);
    }
    for (const CellNodeField& f : m.cell_node_fields) {
      const CellNodeField* g = r.cell_node_field(f.name);
      REQUIRE(g);
      // Gmsh re-writes the view with its own scheme name: the values survive, the degree is
      // only ours to know when our scheme name is kept.
      REQUIRE(g->values.size() == f.values.size());
      for (size_t i = 0; i < f.values.size(); ++i) CHECK(std::abs(g->values[i] - f.values[i]) <= 4 * tol);
    }
  }
  fs::remove(ours);
  fs::remove(ours.string() + ".opt");
}

TEST_CASE("gmsh_call turns Gmsh failures into ExternalError") {
  GmshSession session;
  CHECK_THROWS_AS(gmsh_call("bad view", [] { gmsh::view::getIndex(12345); }), ExternalError);
  GmshSession nested;  // nesting keeps the SDK alive
  CHECK_NOTHROW(gmsh_call("clear", [] { gmsh::clear(); }));
}
