#include "flexgait/experiments/support_polygon.hpp"

#include <algorithm>
#include <array>
#include <cmath>
#include <limits>

#include "flexgait/robot/convex_hull.hpp"

namespace flexgait::experiments {

std::vector<Eigen::Vector2d> support_polygon(const std::vector<walking::Pose>& soles,
                                             const std::vector<const walking::SolePolygon*>& shapes) {
  std::vector<std::array<double, 2>> corners;
  for (std::size_t i = 0; i < soles.size(); ++i)
    for (const Eigen::Vector2d& k : shapes[i]->corners) {
      const Eigen::Vector3d c = soles[i].p + soles[i].R * Eigen::Vector3d(k.x(), k.y(), 0);
      corners.push_back({c.x(), c.y()});
    }
  std::vector<Eigen::Vector2d> hull;
  for (const auto& c : humanoid::convex_hull(std::move(corners))) hull.emplace_back(c[0], c[1]);
  return hull;
}

std::vector<Eigen::Vector2d> support_polygon(const std::vector<walking::Pose>& soles, double length, double width) {
  const walking::SolePolygon rectangle = walking::rectangle_sole(length, width);
  return support_polygon(soles, std::vector<const walking::SolePolygon*>(soles.size(), &rectangle));
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
