#include "flexgait/experiments/capture_point_bound.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <stdexcept>

namespace flexgait::experiments {

double distance_to_edge(const std::vector<Eigen::Vector2d>& polygon, const Eigen::Vector2d& p,
                        const Eigen::Vector2d& direction) {
  if (!(direction.norm() > 0)) throw std::invalid_argument("distance_to_edge: zero direction");
  if (polygon.size() < 3) return 0.0;
  const Eigen::Vector2d u = direction.normalized();
  double s = std::numeric_limits<double>::infinity();
  for (std::size_t i = 0; i < polygon.size(); ++i) {
    const Eigen::Vector2d a = polygon[i], b = polygon[(i + 1) % polygon.size()];
    const Eigen::Vector2d n(b.y() - a.y(), a.x() - b.x());  // outward normal of a ccw edge
    const double outside = n.dot(p - a);                    // > 0: p beyond this edge
    if (outside > 0) return 0.0;
    // On the ray p + s u, n·(p + s u − a) ≤ 0 holds up to s = −outside / n·u when n·u > 0.
    if (n.dot(u) > 0) s = std::min(s, -outside / n.dot(u));
  }
  return std::isfinite(s) ? s : 0.0;
}

CapturePointBound capture_point_bound(double mass, double com_height, double gravity,
                                      const std::vector<Eigen::Vector2d>& polygon, const Eigen::Vector2d& com,
                                      const Eigen::Vector2d& direction) {
  if (!(mass > 0) || !(com_height > 0) || !(gravity > 0))
    throw std::invalid_argument("capture_point_bound: mass, COM height and gravity must be positive");
  CapturePointBound b;
  b.omega0 = std::sqrt(gravity / com_height);
  b.distance = distance_to_edge(polygon, com, direction);
  b.delta_v = b.omega0 * b.distance;
  b.impulse = mass * b.delta_v;
  return b;
}

}  // namespace flexgait::experiments
