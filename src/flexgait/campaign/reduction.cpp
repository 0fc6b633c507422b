#include "flexgait/campaign/reduction.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <limits>
#include <optional>
#include <stdexcept>

#include "flexgait/core/config.hpp"
#include "flexgait/core/text.hpp"

namespace flexgait::campaign {
namespace {

enum class MetricKind { Fraction, Statistics, Skipped };

bool is_boolean(const std::string& cell) {
  return cell == "true" || cell == "false";
}

// A number cell: finite, or nan/inf as format_number writes them (they count in no statistic).
std::optional<double> number_cell(const std::string& cell) {
  if (cell == "nan" || cell == "-nan") return std::numeric_limits<double>::quiet_NaN();
  if (cell == "inf") return std::numeric_limits<double>::infinity();
  if (cell == "-inf") return -std::numeric_limits<double>::infinity();
  return parse_finite_number(cell);
}

// The kind of the metric in `column` of the table's `rows`, from all its non-empty cells.
MetricKind kind_of(const std::vector<CsvRecord>& rows, std::size_t column) {
  bool any = false, booleans = true, numbers = true;
  for (std::size_t r = 1; r < rows.size(); ++r) {
    const std::string& cell = rows[r].fields[column];
    if (cell.empty()) continue;
    any = true;
    booleans = booleans && is_boolean(cell);
    numbers = numbers && number_cell(cell).has_value();
  }
  if (!any) return MetricKind::Skipped;
  if (booleans) return MetricKind::Fraction;
  return numbers ? MetricKind::Statistics : MetricKind::Skipped;
}

// The grid coordinates (one per axis, the first axis slowest) of point i.
std::vector<int> coordinates(const Grid& grid, int i) {
  std::vector<int> c(grid.axes().size());
  for (std::size_t k = grid.axes().size(); k-- > 0;) {
    const int n = static_cast<int>(grid.axes()[k].values.size());
    c[k] = i % n;
    i /= n;
  }
  return c;
}

struct Accumulator {
  int cells = 0, trues = 0, finite = 0;
  double sum = 0, min = std::numeric_limits<double>::infinity(), max = -std::numeric_limits<double>::infinity();
};

}  // namespace

void check_reduction(const Grid& grid, const std::vector<std::string>& over) {
  std::string axes;
  for (const GridAxis& a : grid.axes()) axes += (axes.empty() ? "" : ", ") + a.key;
  for (std::size_t k = 0; k < over.size(); ++k) {
    const auto& all = grid.axes();
    if (std::none_of(all.begin(), all.end(), [&](const GridAxis& a) { return a.key == over[k]; }))
      throw UsageError(
          fmt::format("--reduce: '{}' is not an axis of the campaign; allowed: {}", one_line(over[k]), axes));
    if (std::find(over.begin(), over.begin() + static_cast<std::ptrdiff_t>(k), over[k]) !=
        over.begin() + static_cast<std::ptrdiff_t>(k))
      throw UsageError(fmt::format("--reduce: '{}' is given twice", one_line(over[k])));
  }
}

std::string reduce_campaign_table(const Grid& grid, const std::vector<std::string>& over, const std::string& csv,
                                  std::size_t drawn) {
  check_reduction(grid, over);
  const std::vector<CsvRecord> rows = parse_csv(csv);
  const std::size_t axes = grid.axes().size();
  if (rows.size() != static_cast<std::size_t>(grid.size()) + 1)
    throw std::runtime_error(fmt::format("campaign table: {} rows for {} points", rows.size() - 1, grid.size()));
  const std::size_t width = rows.front().fields.size();  // index, axes, drawn, metrics, error
  for (const CsvRecord& r : rows)
    if (r.fields.size() != width || width < axes + drawn + 2)
      throw std::runtime_error("campaign table: a row with " + std::to_string(r.fields.size()) + " cells");
  const std::size_t first_metric = 1 + axes + drawn, error_column = width - 1;

  std::vector<std::size_t> kept;  // the axes not reduced over, in grid order
  int groups = 1;
  for (std::size_t k = 0; k < axes; ++k)
    if (std::find(over.begin(), over.end(), grid.axes()[k].key) == over.end()) {
      kept.push_back(k);
      groups *= static_cast<int>(grid.axes()[k].values.size());
    }
  std::vector<MetricKind> kinds;
  for (std::size_t m = first_metric; m < error_column; ++m) kinds.push_back(kind_of(rows, m));

  std::vector<int> points(static_cast<std::size_t>(groups), 0), errors(points.size(), 0);
  std::vector<std::vector<Accumulator>> acc(points.size(), std::vector<Accumulator>(kinds.size()));
  for (int i = 0; i < grid.size(); ++i) {
    const CsvRecord& row = rows[static_cast<std::size_t>(i) + 1];
    if (row.fields[0] != std::to_string(i))
      throw std::runtime_error(fmt::format("campaign table: row {} has index '{}'", i, one_line(row.fields[0])));
    const std::vector<int> c = coordinates(grid, i);
    std::size_t g = 0;
    for (std::size_t k : kept) g = g * grid.axes()[k].values.size() + static_cast<std::size_t>(c[k]);
    ++points[g];
    if (!row.fields[error_column].empty()) {
      ++errors[g];
      continue;
    }
    for (std::size_t m = 0; m < kinds.size(); ++m) {
      const std::string& cell = row.fields[first_metric + m];
      if (kinds[m] == MetricKind::Skipped || cell.empty()) continue;
      Accumulator& a = acc[g][m];
      ++a.cells;
      if (kinds[m] == MetricKind::Fraction) {
        a.trues += cell == "true";
      } else if (const double v = *number_cell(cell); std::isfinite(v)) {
        ++a.finite;
        a.sum += v;
        a.min = std::min(a.min, v);
        a.max = std::max(a.max, v);
      }
    }
  }

  std::vector<std::string> header;
  for (std::size_t k : kept) header.push_back(grid.axes()[k].key);
  header.insert(header.end(), {"points", "errors"});
  for (std::size_t m = 0; m < kinds.size(); ++m) {
    const std::string& name = rows.front().fields[first_metric + m];
    if (kinds[m] == MetricKind::Fraction) header.push_back(name + "_fraction");
    if (kinds[m] == MetricKind::Statistics)
      for (const char* s : {"_mean", "_min", "_max"}) header.push_back(name + s);
  }
  CsvWriter out(header);
  for (int g = 0; g < groups; ++g) {
    int rest = g;  // the kept axes' coordinates of group g, the last fastest
    std::vector<std::string> values(kept.size());
    for (std::size_t j = kept.size(); j-- > 0;) {
      const auto& axis_values = grid.axes()[kept[j]].values;
      values[j] = axis_values[static_cast<std::size_t>(rest) % axis_values.size()];
      rest /= static_cast<int>(axis_values.size());
    }
    for (const std::string& v : values) out.cell(v);
    const auto gi = static_cast<std::size_t>(g);
    out.cell(static_cast<long long>(points[gi])).cell(static_cast<long long>(errors[gi]));
    for (std::size_t m = 0; m < kinds.size(); ++m) {
      const Accumulator& a = acc[gi][m];
      if (kinds[m] == MetricKind::Fraction) {
        if (a.cells > 0)
          out.cell(static_cast<double>(a.trues) / a.cells);
        else
          out.cell("");
      } else if (kinds[m] == MetricKind::Statistics) {
        if (a.finite > 0)
          out.cell(a.sum / a.finite).cell(a.min).cell(a.max);
        else
          out.cell("").cell("").cell("");
      }
    }
    out.end_row();
  }
  return out.str();
}

}  // namespace flexgait::campaign
