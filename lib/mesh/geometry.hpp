#pragma once
// The true boundary of a domain: named parametric curves (docs/curved.md, "Geometry").
//
// A BoundaryGeometry is a set of curves c(t), t in [t0, t1], each with the physical name that
// becomes the boundary-group name of the meshes made on it, and the end vertices shared between
// curves (the corners of the boundary; index into vertices(); -1 for a closed curve). The
// implementations: gmsh/geometry.hpp (anything the Gmsh SDK opens: .geo, .brep, .step) and
// FunctionGeometry below (curves given as functions; tests, analytic domains).
//
// Queries are pure functions of the curve and parameter; the closest point is found here once
// for every implementation: the nearest of `kSamples` equispaced parameter samples, then Newton
// on (c(t) - x) . c'(t) = 0 with c'' (converges to rounding on smooth curves), clamped to
// [t0, t1] for open curves.
#include <array>
#include <functional>
#include <string>
#include <vector>

#include "mesh/mesh.hpp"

namespace quadapt {

struct GeometryCurve {
  std::string name;          ///< physical name (= boundary group name)
  int tag = 0;               ///< the entity's tag in its source (messages)
  double t0 = 0, t1 = 1;     ///< parameter range
  std::array<int, 2> ends{{-1, -1}};  ///< vertices at t0 and t1 (index into vertices()); -1: closed
  bool closed() const { return ends[0] < 0; }
};

class BoundaryGeometry {
 public:
  virtual ~BoundaryGeometry() = default;
  /// The file (or description) the geometry came from: messages name it.
  const std::string& source() const { return source_; }
  const std::vector<GeometryCurve>& curves() const { return curves_; }
  const std::vector<Vec2>& vertices() const { return vertices_; }
  int num_curves() const { return static_cast<int>(curves_.size()); }
  /// Sorted distinct physical names of the curves.
  std::vector<std::string> names() const;
  /// Curves called `name` (empty when none).
  std::vector<int> curves_named(const std::string& name) const;

  /// c(t), c'(t), c''(t) of curve k.
  virtual Vec2 point(int k, double t) const = 0;
  virtual Vec2 derivative(int k, double t) const = 0;
  virtual Vec2 second_derivative(int k, double t) const = 0;
  /// Several points at once (implementations may batch; default: point() in a loop).
  virtual std::vector<Vec2> points(int k, const std::vector<double>& t) const;

  /// Parameter of the point of curve k closest to x (see the header comment).
  double closest_parameter(int k, const Vec2& x) const;
  /// The point of the curves in `ks` closest to x; `curve` and `t` receive where it lies.
  Vec2 closest_point(const std::vector<int>& ks, const Vec2& x, int* curve = nullptr, double* t = nullptr) const;

  static constexpr int kSamples = 256;

 protected:
  /// Implementations fill these, then call finish() (caches the closest-point samples).
  std::string source_;
  std::vector<GeometryCurve> curves_;
  std::vector<Vec2> vertices_;
  void finish();

 private:
  std::vector<std::vector<Vec2>> samples_;  // per curve, kSamples + 1 points
};

/// Curves given as functions (value, first and second derivative).
class FunctionGeometry : public BoundaryGeometry {
 public:
  struct Curve {
    std::string name;
    double t0 = 0, t1 = 1;
    std::function<Vec2(double)> c, dc, ddc;
  };
  /// Curves whose end points coincide (to 1e-12 relative to the geometry's size) share a
  /// vertex; a curve whose own ends coincide is closed.
  FunctionGeometry(std::string source, std::vector<Curve> curves);
  Vec2 point(int k, double t) const override { return f_[k].c(t); }
  Vec2 derivative(int k, double t) const override { return f_[k].dc(t); }
  Vec2 second_derivative(int k, double t) const override { return f_[k].ddc(t); }

  /// A circle of radius r about `center`, counter-clockwise, as one closed curve, t in [0, 2 pi].
  static Curve circle(const std::string& name, const Vec2& center, double r);
  /// The straight segment a -> b, t in [0, 1].
  static Curve segment(const std::string& name, const Vec2& a, const Vec2& b);

 private:
  std::vector<Curve> f_;
};

}  // namespace quadapt
