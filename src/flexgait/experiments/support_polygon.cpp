#include "flexgait/experiments/support_polygon.hpp"

#include <algorithm>
#include <cmath>
#include <limits>

namespace flexgait::experiments {

std::vector<Eigen::Vector2d> support_polygon(const std::vector<walking::Pose>& soles, double length, double width) {
  std::vector<Eigen::Vector2d> pts;
  for (const auto& s : soles)
    for (double sx : {-0.5, 0.5})
      for (double sy : {-0.5, 0.5}) pts.push_back((s.p + s.R * Eigen::Vector3d(sx * length, sy * width, 0)).head<2>());
  // Andrew's monotone chain.
  std::sort(pts.begin(), pts.end(),
            [](const auto& a, const auto& b) { return a.x() < b.x() || (a.x() == b.x() && a.y() < b.y()); });
  if (pts.size() < 3) return pts;
  const auto cross = [](const Eigen::Vector2d& o, const Eigen::Vector2d& a, const Eigen::Vector2d& b) {
    return (a - o).x() * (b - o).y() - (a - o).y() * (b - o).x();
  };
  std::vector<Eigen::Vector2d> hull(2 * pts.size());
  std::size_t k = 0;
  for (const auto& p : pts) {
    while (k >= 2 && cross(hull[k - 2], hull[k - 1], p) <= 0) --k;
    hull[k++] = p;
  }
  for (auto i = pts.size() - 1, lower = k + 1; i-- > 0;) {
    while (k >= lower && cross(hull[k - 2], hull[k - 1], pts[i]) <= 0) --k;
    hull[k++] = pts[i];
  }
  hull.resize(k - 1);
  return hull;
}

double support_margin(const std::vector<Eigen::Vector2d>& polygon, const Eigen::Vector2d& p) {
  if (polygon.size() < 3) return std::numeric_limits<double>::quiet_NaN();  // no support, no margin
  double margin = std::numeric_limits<double>::infinity();
  for (std::size_t i = 0; i < polygon.size(); ++i) {
    const Eigen::Vector2d a = polygon[i], b = polygon[(i + 1) % polygon.size()];
    const Eigen::Vector2d e = (b - a).normalized();
    // Distance to the edge's line, positive on the left (inside of a ccw polygon).
    margin = std::min(margin, e.x() * (p - a).y() - e.y() * (p - a).x());
  }
  return margin;
}

}  // namespace flexgait::experiments
