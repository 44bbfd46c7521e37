#include "gmsh/geometry.hpp"

#include <gmsh.h>

#include <cmath>
#include <map>

#include "core/error.hpp"
#include "gmsh/plugin.hpp"
#include "gmsh/session.hpp"

namespace quadapt {

namespace {

const char* const kModel = "quadapt-geometry";

class GmshGeometry : public BoundaryGeometry {
 public:
  explicit GmshGeometry(const std::string& path);
  ~GmshGeometry() override;
  Vec2 point(int k, double t) const override { return eval(k, t, 0); }
  Vec2 derivative(int k, double t) const override { return eval(k, t, 1); }
  Vec2 second_derivative(int k, double t) const override { return eval(k, t, 2); }
  std::vector<Vec2> points(int k, const std::vector<double>& t) const override;

 private:
  GmshSession session_;
  void load(const std::string& path);
  Vec2 eval(int k, double t, int order) const;
};

GmshGeometry::GmshGeometry(const std::string& path) {
  try {
    load(path);
  } catch (...) {
    remove_gmsh_model(kModel);  // the session member still lives here
    throw;
  }
}

void GmshGeometry::load(const std::string& path) {
  source_ = path;
  std::map<int, std::string> curve_name;     // entity tag -> physical name
  std::vector<std::pair<int, Vec2>> points;  // point entities
  std::string problem;
  try {
    gmsh_call("open " + path, [&] {
      gmsh::model::add(kModel);
      gmsh::merge(path);
      gmsh::vectorpair groups;
      gmsh::model::getPhysicalGroups(groups, 1);
      for (const auto& [dim, ptag] : groups) {
        std::string name;
        gmsh::model::getPhysicalName(1, ptag, name);
        if (name.empty()) {
          problem = "physical curve " + std::to_string(ptag) + " has no name (the names become the boundary names)";
          return;
        }
        std::vector<int> tags;
        gmsh::model::getEntitiesForPhysicalGroup(1, ptag, tags);
        for (int t : tags) {
          auto it = curve_name.find(t);
          if (it != curve_name.end() && it->second != name) {
            problem =
                "curve " + std::to_string(t) + " belongs to two physical groups ('" + it->second + "', '" + name + "')";
            return;
          }
          curve_name[t] = name;
        }
      }
      gmsh::vectorpair pts;
      gmsh::model::getEntities(pts, 0);
      for (const auto& [dim, tag] : pts) {
        std::vector<double> xyz, none;
        gmsh::model::getValue(0, tag, none, xyz);
        if (xyz.size() == 3) points.emplace_back(tag, Vec2(xyz[0], xyz[1]));
      }
    });
  } catch (const ExternalError& e) {
    throw InputError(path, std::string("Gmsh cannot open it (") + e.what() + ")");
  }
  if (!problem.empty()) throw InputError(path, problem);
  if (curve_name.empty())
    throw InputError(path,
                     "no named physical curves (the boundary names of "
                     "the mesh come from them)");
  double size = 1;
  for (auto& [tag, p] : points) size = std::max(size, p.norm());
  gmsh_call("curves of " + path, [&] {
    for (const auto& [tag, name] : curve_name) {
      GeometryCurve c;
      c.name = name;
      c.tag = tag;
      std::vector<double> lo, hi;
      gmsh::model::getParametrizationBounds(1, tag, lo, hi);
      c.t0 = lo.at(0);
      c.t1 = hi.at(0);
      curves_.push_back(c);
    }
  });
  // ends: the point entities at c(t0), c(t1) (corners shared between curves,
  // exact coordinates)
  std::map<int, int> vertex_of;  // point tag -> vertex index
  const double tol = 1e-9 * size;
  for (int k = 0; k < num_curves(); ++k) {
    auto& c = curves_[k];
    std::vector<Vec2> e = this->points(k, {c.t0, c.t1});
    if ((e[0] - e[1]).norm() <= tol) continue;  // closed
    for (int s = 0; s < 2; ++s) {
      int best = -1;
      double bd = tol;
      for (auto& [tag, p] : points)
        if ((p - e[s]).norm() <= bd) {
          bd = (p - e[s]).norm();
          best = tag;
        }
      if (best < 0) {  // no point entity there (e.g. an OCC curve's own end):
                       // its own vertex
        vertices_.push_back(e[s]);
        c.ends[s] = static_cast<int>(vertices_.size()) - 1;
        continue;
      }
      auto it = vertex_of.find(best);
      if (it == vertex_of.end()) {
        for (auto& [tag, p] : points)
          if (tag == best) vertices_.push_back(p);
        it = vertex_of.emplace(best, static_cast<int>(vertices_.size()) - 1).first;
      }
      c.ends[s] = it->second;
    }
  }
  finish();
}

// its model goes with it (a caller's own Gmsh keeps its models only); the session member ends after this body
GmshGeometry::~GmshGeometry() { remove_gmsh_model(kModel); }

Vec2 GmshGeometry::eval(int k, double t, int order) const {
  std::vector<double> v;
  gmsh_call("curve " + std::to_string(curves_[k].tag), [&] {
    gmsh::model::setCurrent(kModel);
    if (order == 0)
      gmsh::model::getValue(1, curves_[k].tag, {t}, v);
    else if (order == 1)
      gmsh::model::getDerivative(1, curves_[k].tag, {t}, v);
    else
      gmsh::model::getSecondDerivative(1, curves_[k].tag, {t}, v);
  });
  if (v.size() < 3) throw ExternalError("Gmsh: no value on curve " + std::to_string(curves_[k].tag) + " of " + source_);
  if (order == 0 && std::abs(v[2]) > 1e-9 * std::max(1.0, std::abs(v[0]) + std::abs(v[1])))
    throw InputError(source_, "curve " + std::to_string(curves_[k].tag) + " is not in the plane z = 0");
  return Vec2(v[0], v[1]);
}

std::vector<Vec2> GmshGeometry::points(int k, const std::vector<double>& t) const {
  std::vector<double> v;
  gmsh_call("curve " + std::to_string(curves_[k].tag), [&] {
    gmsh::model::setCurrent(kModel);
    gmsh::model::getValue(1, curves_[k].tag, t, v);
  });
  if (v.size() != 3 * t.size())
    throw ExternalError("Gmsh: no values on curve " + std::to_string(curves_[k].tag) + " of " + source_);
  std::vector<Vec2> r(t.size());
  for (size_t i = 0; i < t.size(); ++i) {
    if (std::abs(v[3 * i + 2]) > 1e-9 * std::max(1.0, std::abs(v[3 * i]) + std::abs(v[3 * i + 1])))
      throw InputError(source_, "curve " + std::to_string(curves_[k].tag) + " is not in the plane z = 0");
    r[i] = Vec2(v[3 * i], v[3 * i + 1]);
  }
  return r;
}

}  // namespace

std::unique_ptr<BoundaryGeometry> gmsh_plugin::sdk_open_geometry(const std::string& path) {
  return std::make_unique<GmshGeometry>(path);
}

}  // namespace quadapt
