#include "flexgait/campaign/random_design.hpp"

#include <fmt/format.h>

#include <set>

#include "flexgait/core/config.hpp"
#include "flexgait/core/text.hpp"

namespace flexgait::campaign {
namespace {

// SplitMix64's finaliser (Steele, Lea and Flood 2014): a bijection of 64-bit words whose output
// passes BigCrush as a counter-based generator.
std::uint64_t mix(std::uint64_t z) {
  z += 0x9e3779b97f4a7c15ULL;
  z = (z ^ (z >> 30)) * 0xbf58476d1ce4e5b9ULL;
  z = (z ^ (z >> 27)) * 0x94d049bb133111ebULL;
  return z ^ (z >> 31);
}

}  // namespace

RandomAxis parse_random_axis(const std::string& text) {
  const auto fail = [&](const std::string& why) {
    return UsageError(fmt::format("--random '{}': {}; allowed: KEY=A:B (a real key drawn uniformly from [A, B])",
                                  one_line(text), why));
  };
  const std::optional<KeyValue> kv = split_key_value(text);
  if (!kv) throw fail("no '='");
  RandomAxis axis{kv->key, 0, 0, text};
  if (axis.key.empty()) throw fail("empty key");
  const auto ends = split_text(kv->value, ':');
  if (ends.size() != 2) throw fail(fmt::format("the range of {} needs exactly A:B", axis.key));
  const auto a = parse_finite_number(ends[0]), b = parse_finite_number(ends[1]);
  if (!a || !b) throw fail(fmt::format("the ends of the range of {} are not finite numbers", axis.key));
  if (!(*a < *b)) throw fail(fmt::format("the range of {} is empty (A must be less than B)", axis.key));
  axis.low = *a;
  axis.high = *b;
  return axis;
}

RandomDesign::RandomDesign(std::vector<RandomAxis> axes, int samples, std::uint64_t seed)
    : axes_(std::move(axes)), samples_(samples), seed_(seed) {
  if (axes_.empty()) {
    if (samples_ != 0) throw UsageError("--samples: given without a --random axis; add one, e.g. --random KEY=A:B");
    return;
  }
  if (samples_ < 1 || samples_ > 100000)
    throw UsageError(fmt::format("--samples: {} with --random axes; allowed: an integer in [1, 100000]", samples_));
  std::set<std::string> keys;
  for (const RandomAxis& a : axes_)
    if (!keys.insert(a.key).second) throw UsageError(fmt::format("--random: key '{}' given twice", one_line(a.key)));
}

GridAxis RandomDesign::sample_axis() const {
  GridAxis axis{kSampleAxis, {}, fmt::format("{}=0:{}:{}", kSampleAxis, samples_ - 1, samples_)};
  for (int s = 0; s < samples_; ++s) axis.values.push_back(std::to_string(s));
  return axis;
}

double RandomDesign::uniform(int sample, std::size_t k) const {
  const std::uint64_t word = mix(mix(mix(seed_) ^ static_cast<std::uint64_t>(sample)) ^ static_cast<std::uint64_t>(k));
  return static_cast<double>(word >> 11) * 0x1.0p-53;
}

std::string RandomDesign::value(int sample, std::size_t k) const {
  const RandomAxis& a = axes_[k];
  return format_number(a.low + (a.high - a.low) * uniform(sample, k));
}

}  // namespace flexgait::campaign
