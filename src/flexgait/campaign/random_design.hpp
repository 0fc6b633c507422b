#pragma once
/// \file random_design.hpp
/// Random points of a campaign (Monte Carlo over keys nobody controls: a push's force, direction
/// and time): `--random KEY=A:B` draws KEY uniformly from [A, B] for each of `--samples N`
/// samples, from `--seed S`. The samples are one more grid axis, `sample` (values 0 .. N-1, the
/// last and fastest axis), so a campaign crosses them with its --grid axes and `--reduce sample`
/// gives rates over the draws. Sample s draws the same values at every grid point (common random
/// numbers: compensation off and both meet the same pushes). The draw of key k at sample s is
/// u = SplitMix64(seed, s, k) in [0, 1) (53 bits), value = A + (B - A) u: a function of
/// (seed, s, k) alone, so the same bytes whatever the threads, ranks and resumes. Real keys only
/// (an integer key such as a seed is a --grid range).
#include <cstdint>
#include <string>
#include <vector>

#include "flexgait/campaign/grid.hpp"

namespace flexgait::campaign {

struct RandomAxis {
  std::string key;    ///< configuration key (dotted)
  double low = 0;     ///< A
  double high = 0;    ///< B
  std::string given;  ///< the --random argument as written
};

/// Parses one --random argument, KEY=A:B (finite A < B); throws UsageError naming it.
RandomAxis parse_random_axis(const std::string& text);

class RandomDesign {
 public:
  /// No random keys.
  RandomDesign() = default;
  /// Throws UsageError: samples not in [1, 100000], a key given twice, or axes without samples.
  RandomDesign(std::vector<RandomAxis> axes, int samples, std::uint64_t seed);

  static constexpr const char* kSampleAxis = "sample";
  bool empty() const { return axes_.empty(); }
  const std::vector<RandomAxis>& axes() const { return axes_; }
  int samples() const { return samples_; }
  std::uint64_t seed() const { return seed_; }
  /// The grid axis of the samples: key "sample", values "0" .. "N-1".
  GridAxis sample_axis() const;
  /// The uniform number u in [0, 1) of axis k at sample s.
  double uniform(int sample, std::size_t k) const;
  /// The value of axis k at sample s as configuration text (round-trip exact).
  std::string value(int sample, std::size_t k) const;

 private:
  std::vector<RandomAxis> axes_;
  int samples_ = 0;
  std::uint64_t seed_ = 0;
};

}  // namespace flexgait::campaign
