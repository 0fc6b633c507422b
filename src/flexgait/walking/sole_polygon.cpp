#include "flexgait/walking/sole_polygon.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <utility>

#include "flexgait/robot/convex_hull.hpp"

namespace flexgait::walking {
namespace {

using Eigen::Vector2d;

/// (b − a) × (p − a): > 0 when p is left of the line a → b (inside a counter-clockwise edge).
double cross(const Vector2d& a, const Vector2d& b, const Vector2d& p) {
  return (b.x() - a.x()) * (p.y() - a.y()) - (b.y() - a.y()) * (p.x() - a.x());
}

/// The point of the segment a b nearest p.
Vector2d nearest_on_segment(const Vector2d& a, const Vector2d& b, const Vector2d& p) {
  const Vector2d e = b - a;
  const double n2 = e.squaredNorm();
  if (!(n2 > 0)) return a;
  return a + std::clamp((p - a).dot(e) / n2, 0.0, 1.0) * e;
}

SolePolygon hull_of(std::vector<Vector2d> points) {
  SolePolygon out;
  out.corners.resize(2 * points.size());
  out.corners.resize(humanoid::convex_hull_into(points.data(), points.size(), out.corners.data()));
  return out;
}

bool contains_corners(const Vector2d* corners, std::size_t n, const Vector2d& p, double scale) {
  if (n < 3) return false;  // a point or a segment: no area
  for (std::size_t i = 0; i < n; ++i)
    if (cross(scale * corners[i], scale * corners[(i + 1) % n], p) < 0) return false;
  return true;
}

}  // namespace

SolePolygon rectangle_sole(double length, double width) {
  SolePolygon s;
  s.rectangle = true;
  s.half = Vector2d(0.5 * length, 0.5 * width);
  const double a = s.half.x(), b = s.half.y();
  s.corners = {Vector2d(-a, -b), Vector2d(a, -b), Vector2d(a, b), Vector2d(-a, b)};
  return s;
}

SolePolygon polygon_sole(const std::vector<Vector2d>& points) {
  SolePolygon s = hull_of(points);
  // convex_hull starts at the lowest x, then lowest y: a centred rectangle's corners in this order.
  if (s.corners.size() == 4) {
    const double a = s.corners[2].x(), b = s.corners[2].y();
    if (s.corners[0] == Vector2d(-a, -b) && s.corners[1] == Vector2d(a, -b) && s.corners[3] == Vector2d(-a, b)) {
      s.rectangle = true;
      s.half = Vector2d(a, b);
    }
  }
  return s;
}

bool contains(const SolePolygon& sole, const Vector2d& p) {
  return contains_scaled(sole, p, 0.5);
}

bool contains_scaled(const SolePolygon& sole, const Vector2d& p, double share) {
  if (sole.rectangle)  // (2 half is the length exactly: half = 0.5 length)
    return std::abs(p.x()) <= share * (2 * sole.half.x()) && std::abs(p.y()) <= share * (2 * sole.half.y());
  return contains_corners(sole.corners.data(), sole.corners.size(), p, 2 * share);
}

Vector2d nearest_point(const SolePolygon& sole, const Vector2d& p) {
  if (sole.rectangle)
    return Vector2d(std::clamp(p.x(), -sole.half.x(), sole.half.x()), std::clamp(p.y(), -sole.half.y(), sole.half.y()));
  return nearest_point(sole.corners.data(), sole.corners.size(), p);
}

Vector2d nearest_point(const Vector2d* corners, std::size_t n, const Vector2d& p) {
  if (n == 0) return p;
  if (n == 1) return corners[0];
  if (contains_corners(corners, n, p, 1.0)) return p;
  Vector2d best = corners[0];
  double best_d2 = std::numeric_limits<double>::infinity();
  for (std::size_t i = 0; i < (n == 2 ? 1 : n); ++i) {
    const Vector2d q = nearest_on_segment(corners[i], corners[(i + 1) % n], p);
    const double d2 = (q - p).squaredNorm();
    if (d2 < best_d2) {
      best_d2 = d2;
      best = q;
    }
  }
  return best;
}

double signed_distance(const SolePolygon& sole, const Vector2d& p) {
  const std::size_t n = sole.corners.size();
  if (n >= 3 && contains(sole, p)) {
    // Inside a convex polygon the nearest edge point is the foot of the nearest edge line.
    double d = std::numeric_limits<double>::infinity();
    for (std::size_t i = 0; i < n; ++i) {
      const Vector2d &a = sole.corners[i], &b = sole.corners[(i + 1) % n];
      d = std::min(d, cross(a, b, p) / (b - a).norm());
    }
    return d;
  }
  return -(p - nearest_point(sole, p)).norm();
}

SolePolygon inset(const SolePolygon& sole, double margin) {
  if (sole.rectangle) {
    SolePolygon s = rectangle_sole(0, 0);
    s.half = (sole.half - Vector2d::Constant(margin)).cwiseMax(0.0);
    const double a = s.half.x(), b = s.half.y();
    s.corners = {Vector2d(-a, -b), Vector2d(a, -b), Vector2d(a, b), Vector2d(-a, b)};
    return s;
  }
  // Sutherland and Hodgman (1974), "Reentrant polygon clipping": the polygon clipped by each of
  // its edges' half-planes moved inward by `margin`.
  const std::size_t n = sole.corners.size();
  std::vector<Vector2d> poly = sole.corners, next;
  for (std::size_t i = 0; i < n && poly.size() >= 3 && n >= 3; ++i) {
    const Vector2d &a = sole.corners[i], &b = sole.corners[(i + 1) % n];
    const double length = (b - a).norm();
    auto inside = [&](const Vector2d& q) { return cross(a, b, q) / length - margin; };
    next.clear();
    for (std::size_t k = 0; k < poly.size(); ++k) {
      const Vector2d &P = poly[k], &Q = poly[(k + 1) % poly.size()];
      const double dp = inside(P), dq = inside(Q);
      if (dp >= 0) next.push_back(P);
      if ((dp >= 0) != (dq >= 0)) next.push_back(P + (Q - P) * (dp / (dp - dq)));
    }
    poly.swap(next);
  }
  if (poly.size() < 3 || n < 3) {
    Vector2d mean = Vector2d::Zero();
    for (const Vector2d& c : sole.corners) mean += c;
    SolePolygon s;
    s.corners = {n > 0 ? Vector2d(mean / static_cast<double>(n)) : mean};
    return s;
  }
  return hull_of(std::move(poly));
}

}  // namespace flexgait::walking
