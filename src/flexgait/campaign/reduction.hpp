#pragma once
/// \file reduction.hpp
/// A campaign table reduced over some of its axes: the rate of an outcome over the seeds of a
/// rough floor or over random pushes (the campaign's `sample` axis, random_design.hpp), the spread
/// of a metric over a parameter nobody controls. One row per combination of the other axes, in
/// grid order (none left: one row), with these columns:
///   the axes kept; `points` (the points reduced into the row); `errors` (those that could not run,
///   a non-empty `error` cell: they count in no statistic below);
///   per metric whose cells are all true/false: `M_fraction`, the fraction of true among the row's
///   points that have the cell (`fell_fraction` is a fall rate);
///   per metric whose cells are all numbers: `M_mean`, `M_min`, `M_max` over the finite cells;
///   text, list and empty metrics are left out.
/// A statistic of no cell is empty. Numbers as format_number; sums in index order, so the bytes
/// do not depend on threads, ranks or resumes (campaign.csv's do not).
#include <string>
#include <vector>

#include "flexgait/campaign/grid.hpp"

namespace flexgait::campaign {

/// Throws UsageError naming a key of `over` that is not an axis of `grid`, or is given twice.
void check_reduction(const Grid& grid, const std::vector<std::string>& over);

/// reduced.csv's text from campaign.csv's (its header, then one row per point of `grid`, sorted by
/// index, as run_campaign writes it: index, the grid's axes, `drawn` columns of random keys — in no
/// statistic —, the metrics, error). Throws std::runtime_error if the table does not have the
/// grid's rows.
std::string reduce_campaign_table(const Grid& grid, const std::vector<std::string>& over, const std::string& csv,
                                  std::size_t drawn = 0);

}  // namespace flexgait::campaign
