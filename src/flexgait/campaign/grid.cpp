#include "flexgait/campaign/grid.hpp"

#include <fmt/format.h>

#include <cmath>
#include <set>

#include "flexgait/core/config.hpp"
#include "flexgait/core/text.hpp"

namespace flexgait::campaign {

GridAxis parse_grid_axis(const std::string& text) {
  const auto fail = [&](const std::string& why) {
    return UsageError(fmt::format("--grid '{}': {}; allowed: KEY=A:B:N (N values from A to B) or KEY=v1,v2,...",
                                  one_line(text), why));
  };
  const std::optional<KeyValue> kv = split_key_value(text);
  if (!kv) throw fail("no '='");
  GridAxis axis{kv->key, {}, text};
  const std::string& values = kv->value;
  if (axis.key.empty()) throw fail("empty key");
  const auto range = split_text(values, ':');
  if (range.size() == 3 && values.find(',') == std::string::npos) {
    const auto a = parse_finite_number(range[0]), b = parse_finite_number(range[1]), n = parse_finite_number(range[2]);
    if (!a || !b) throw fail(fmt::format("the ends of the range of {} are not finite numbers", axis.key));
    if (!n || *n != std::floor(*n) || *n < 1 || *n > 100000)
      throw fail(fmt::format("the count of {} is not an integer in [1, 100000]", axis.key));
    const int count = static_cast<int>(*n);
    // 15 significant digits: 0.3:0.9:4 gives 0.5 and 0.7, not 0.7000000000000001 (the rounding of
    // A + (B - A) i / (N - 1) in doubles); the value text is what the configuration reads.
    for (int i = 0; i < count; ++i)
      axis.values.push_back(
          fmt::format("{:.15g}", i == count - 1 && count > 1 ? *b : *a + (*b - *a) * i / std::max(1, count - 1)));
    return axis;
  }
  if (range.size() != 1) throw fail(fmt::format("a range of {} needs exactly A:B:N", axis.key));
  axis.values = split_text(values, ',');
  for (const auto& v : axis.values)
    if (v.empty()) throw fail(fmt::format("an empty value of {}", axis.key));
  return axis;
}

Grid::Grid(std::vector<GridAxis> axes) : axes_(std::move(axes)) {
  if (axes_.empty())
    throw UsageError("campaign: no --grid or --random axis; give at least one, e.g. --grid rimless.mu=0.2:1:9");
  std::set<std::string> keys;
  std::int64_t n = 1;
  for (const auto& a : axes_) {
    if (!keys.insert(a.key).second) throw UsageError(fmt::format("--grid: key '{}' given twice", one_line(a.key)));
    n *= static_cast<std::int64_t>(a.values.size());
    if (n > kMaxPoints)
      throw UsageError(fmt::format("--grid: more than {} points; allowed: at most {}", kMaxPoints, kMaxPoints));
  }
  size_ = static_cast<int>(n);
}

std::vector<std::string> Grid::point(int i) const {
  std::vector<std::string> out(axes_.size());
  for (std::size_t k = axes_.size(); k-- > 0;) {  // last axis fastest
    const int n = static_cast<int>(axes_[k].values.size());
    out[k] = axes_[k].values[static_cast<std::size_t>(i % n)];
    i /= n;
  }
  return out;
}

}  // namespace flexgait::campaign
