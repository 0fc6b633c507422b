#include "flexgait/robot/convex_hull.hpp"

#include <algorithm>

namespace flexgait::humanoid {

std::vector<std::array<double, 2>> convex_hull(std::vector<std::array<double, 2>> pts) {
  std::vector<std::array<double, 2>> hull(2 * pts.size());
  hull.resize(convex_hull_into(pts.data(), pts.size(), hull.data()));
  return hull;
}

double polygon_area(const std::vector<std::array<double, 2>>& polygon) {
  double twice = 0;
  for (std::size_t i = 0; i < polygon.size(); ++i) {
    const auto& a = polygon[i];
    const auto& b = polygon[(i + 1) % polygon.size()];
    twice += a[0] * b[1] - a[1] * b[0];
  }
  return 0.5 * twice;
}

}  // namespace flexgait::humanoid
