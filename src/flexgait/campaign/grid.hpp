#pragma once
/// \file grid.hpp
/// The grid of a campaign: axes given as `KEY=A:B:N` (N values from A to B, evenly spaced, ends
/// exact) or `KEY=v1,v2,...` (the values as written: numbers, names of a choice, true/false), and
/// their Cartesian product, the first axis varying slowest (point index = row-major order).
#include <cstdint>
#include <string>
#include <vector>

namespace flexgait::campaign {

struct GridAxis {
  std::string key;                  ///< configuration key (dotted)
  std::vector<std::string> values;  ///< the values as configuration text, in order
  std::string given;                ///< the --grid argument as written
};

/// Parses one --grid argument; throws UsageError naming it: no '=', an empty key or value, a
/// range whose ends are not finite numbers or whose N is not an integer in [1, 100000].
GridAxis parse_grid_axis(const std::string& text);

/// The Cartesian product of axes.
class Grid {
 public:
  /// Throws UsageError if there is no axis, a key is given twice or the product exceeds
  /// kMaxPoints points.
  explicit Grid(std::vector<GridAxis> axes);
  static constexpr std::int64_t kMaxPoints = 1'000'000;
  const std::vector<GridAxis>& axes() const { return axes_; }
  int size() const { return size_; }
  /// The value of every axis at point i (0 <= i < size()), in axis order.
  std::vector<std::string> point(int i) const;

 private:
  std::vector<GridAxis> axes_;
  int size_ = 0;
};

}  // namespace flexgait::campaign
