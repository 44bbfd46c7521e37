#include "mesh/geometry.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <set>

#include "core/error.hpp"

namespace quadapt {

std::vector<std::string> BoundaryGeometry::names() const {
  std::set<std::string> s;
  for (const auto& c : curves_) s.insert(c.name);
  return {s.begin(), s.end()};
}

std::vector<int> BoundaryGeometry::curves_named(const std::string& name) const {
  std::vector<int> r;
  for (int k = 0; k < num_curves(); ++k)
    if (curves_[k].name == name) r.push_back(k);
  return r;
}

std::vector<Vec2> BoundaryGeometry::points(int k, const std::vector<double>& t) const {
  std::vector<Vec2> r;
  r.reserve(t.size());
  for (double s : t) r.push_back(point(k, s));
  return r;
}

void BoundaryGeometry::finish() {
  samples_.clear();
  for (int k = 0; k < num_curves(); ++k) {
    const auto& c = curves_[k];
    std::vector<double> t(kSamples + 1);
    for (int i = 0; i <= kSamples; ++i) t[i] = c.t0 + (c.t1 - c.t0) * i / kSamples;
    samples_.push_back(points(k, t));
  }
}

double BoundaryGeometry::closest_parameter(int k, const Vec2& x) const {
  const auto& c = curves_[k];
  const auto& S = samples_.at(k);
  int best = 0;
  double bd = std::numeric_limits<double>::infinity();
  for (int i = 0; i <= kSamples; ++i) {
    double d = (S[i] - x).squaredNorm();
    if (d < bd) {
      bd = d;
      best = i;
    }
  }
  const double dt = (c.t1 - c.t0) / kSamples;
  double t = c.t0 + dt * best;
  double lo = c.t0, hi = c.t1;
  if (!c.closed()) {
    lo = std::max(c.t0, t - dt);
    hi = std::min(c.t1, t + dt);
  } else {
    lo = t - dt;
    hi = t + dt;
  }
  // Newton on f(t) = (c(t) - x) . c'(t), safeguarded to the bracket [lo, hi]; a closed
  // curve's bracket may cross its seam: evaluate there at t -+ period
  const double period = c.t1 - c.t0;
  auto wrap = [&](double u) { return !c.closed() ? u : u < c.t0 ? u + period : u > c.t1 ? u - period : u; };
  for (int it = 0; it < 50; ++it) {
    const double tw = wrap(t);
    Vec2 r = point(k, tw) - x, d1 = derivative(k, tw), d2 = second_derivative(k, tw);
    double f = r.dot(d1), fp = d1.squaredNorm() + r.dot(d2);
    double tn = fp > 0 ? t - f / fp : t - f / std::max(d1.squaredNorm(), 1e-300);
    tn = std::clamp(tn, lo, hi);
    if (std::abs(tn - t) <= 1e-15 * std::max(1.0, std::abs(t)) + 1e-300) {
      t = tn;
      break;
    }
    t = tn;
  }
  if (c.closed()) {  // back into [t0, t1)
    const double P = c.t1 - c.t0;
    if (t < c.t0) t += P;
    if (t >= c.t1) t -= P;
  }
  return t;
}

Vec2 BoundaryGeometry::closest_point(const std::vector<int>& ks, const Vec2& x, int* curve, double* t) const {
  double bd = std::numeric_limits<double>::infinity();
  Vec2 best = x;
  for (int k : ks) {
    double s = closest_parameter(k, x);
    Vec2 p = point(k, s);
    // end points: the vertices themselves (exact corners)
    const auto& c = curves_[k];
    if (!c.closed()) {
      if (s == c.t0) p = vertices_[c.ends[0]];
      if (s == c.t1) p = vertices_[c.ends[1]];
    }
    double d = (p - x).squaredNorm();
    if (d < bd) {
      bd = d;
      best = p;
      if (curve) *curve = k;
      if (t) *t = s;
    }
  }
  return best;
}

FunctionGeometry::FunctionGeometry(std::string source, std::vector<Curve> curves) : f_(std::move(curves)) {
  source_ = std::move(source);
  double size = 0;
  for (const auto& f : f_) size = std::max({size, f.c(f.t0).norm(), f.c(f.t1).norm(), 1.0});
  const double tol = 1e-12 * size;
  auto vertex = [&](const Vec2& p) {
    for (int i = 0; i < static_cast<int>(vertices_.size()); ++i)
      if ((vertices_[i] - p).norm() <= tol) return i;
    vertices_.push_back(p);
    return static_cast<int>(vertices_.size()) - 1;
  };
  int tag = 0;
  for (const auto& f : f_) {
    GeometryCurve c;
    c.name = f.name;
    c.tag = ++tag;
    c.t0 = f.t0;
    c.t1 = f.t1;
    Vec2 a = f.c(f.t0), b = f.c(f.t1);
    if ((a - b).norm() > tol) c.ends = {vertex(a), vertex(b)};
    curves_.push_back(c);
  }
  finish();
}

FunctionGeometry::Curve FunctionGeometry::circle(const std::string& name, const Vec2& o, double r) {
  Curve c;
  c.name = name;
  c.t0 = 0;
  c.t1 = 2 * M_PI;
  c.c = [o, r](double t) { return Vec2(o + r * Vec2(std::cos(t), std::sin(t))); };
  c.dc = [r](double t) { return Vec2(r * Vec2(-std::sin(t), std::cos(t))); };
  c.ddc = [r](double t) { return Vec2(-r * Vec2(std::cos(t), std::sin(t))); };
  return c;
}

FunctionGeometry::Curve FunctionGeometry::segment(const std::string& name, const Vec2& a, const Vec2& b) {
  Curve c;
  c.name = name;
  c.c = [a, b](double t) { return Vec2(a + t * (b - a)); };
  c.dc = [a, b](double) { return Vec2(b - a); };
  c.ddc = [](double) { return Vec2(0, 0); };
  return c;
}

}  // namespace quadapt
