// Seeded fuzzing of the configuration reader in process: YAML texts made by damaging the
// shipped configurations (byte flips, YAML tokens, anchors and aliases, spliced chunks) and --set
// items with malformed values, through parse_config_yaml and resolve_config. Every input must give
// a configuration or a ConfigError/UsageError whose message is one line; any other exception, or
// a crash (found under ASan/UBSan), is a failure. Deterministic for a seed; runs cases 0, 1, ...
// until the time budget is spent.
//
// Usage: config_fuzz SOURCE_DIR [SECONDS=20] [SEED=17] [CASE]  (CASE: replay one case and print it)
#include <chrono>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <random>
#include <string>
#include <vector>

#include "flexgait/core/atomic_file.hpp"
#include "flexgait/core/config.hpp"
#include "flexgait/core/config_file.hpp"
#include "flexgait/rimless/wheel_setup.hpp"
#include "flexgait/twin/disturbance.hpp"

namespace {

using flexgait::ConfigEntry;

// A key of type list (disturbance.pushes) beside the rimless keys, so the list reader is fuzzed too.
struct PushList {
  std::vector<flexgait::twin::Push> pushes;
  template <class Self, class Visit>
  static void visit_fields(Self& s, Visit& v) {
    v("disturbance.pushes", s.pushes, {.doc = "pushes"});
  }
};

const std::vector<std::string> kTokens = {
    "\n",     ":",    ": ",   "- ",    "&a ", "*a",       "&b ",   "*b",    "{",    "}",
    "[",      "]",    ",",    "'",     "\"",  "#",        "---\n", "...\n", "? ",   "!!str ",
    "!!map ", "<<: ", "|\n",  ">\n",   "\t",  "\\",       "\x00",  "\xff",  "\xc3", "~",
    "null",   "nan",  ".inf", "1e400", "  ",  "rimless.", "K",     "mu_s",  "legs", "%YAML 1.2\n"};
const std::vector<std::string> kValues = {
    "",     "nan",   "inf",    "-1",
    "0",    "1e308", "1e-320", "abc",
    "1,2",  "true",  "rigid",  "3",
    "0.5",  "+1",    "1\n2",   std::string(5000, '9'),
    "\x01", "=",     "-0",     "[{time: 1, body: chest, force: [0, 1, 0], duration: 0.1}]",
    "[]",   "[{",    "[[1]]"};

std::string mutate(std::mt19937_64& rng, const std::vector<std::string>& corpus) {
  auto pick = [&](std::size_t n) { return static_cast<std::size_t>(rng() % n); };
  std::string text = corpus[pick(corpus.size())];
  const int edits = 1 + static_cast<int>(pick(8));
  for (int e = 0; e < edits; ++e) {
    const std::size_t at = text.empty() ? 0 : pick(text.size() + 1);
    switch (pick(5)) {
      case 0:
        text.insert(at, kTokens[pick(kTokens.size())]);
        break;
      case 1:
        if (at < text.size()) text[at] = static_cast<char>(rng());
        break;
      case 2:
        if (at < text.size()) text.erase(at, 1 + pick(16));
        break;
      case 3: {  // splice a chunk of another corpus entry
        const std::string& other = corpus[pick(corpus.size())];
        const std::size_t from = pick(other.size() + 1);
        text.insert(at, other.substr(from, pick(200)));
        break;
      }
      default: {  // repeat a chunk (duplicate keys, deep nesting, alias fan-out)
        const std::size_t len = pick(64);
        const std::string chunk = text.substr(at, len);
        for (std::size_t r = pick(20); r > 0; --r) text.insert(at, chunk);
      }
    }
  }
  return text;
}

// One case: empty if it behaved, else what went wrong.
std::string run_case(std::uint64_t seed, std::uint64_t k, const std::vector<std::string>& corpus,
                     const flexgait::Schema& schema, bool print) {
  std::mt19937_64 rng(seed * 1000003 + k);
  const std::string text = mutate(rng, corpus);
  std::vector<std::string> sets;
  for (std::size_t n = rng() % 3; n > 0; --n) {
    const auto& params = schema.params();
    const std::string key = rng() % 10 == 0 ? "no.such" : params[rng() % params.size()].key;
    sets.push_back(key + (rng() % 20 == 0 ? "" : "=") + kValues[rng() % kValues.size()]);
  }
  if (print) std::printf("YAML (%zu bytes):\n%s\n--set: %zu items\n", text.size(), text.c_str(), sets.size());
  try {
    const std::vector<ConfigEntry> entries = flexgait::parse_config_yaml(text, "fuzz.yaml");
    const flexgait::Config c = flexgait::resolve_config(schema, std::nullopt, sets, entries);
    (void)c.to_yaml();
  } catch (const flexgait::UsageError& e) {
    const std::string what = e.what();
    if (what.find('\n') != std::string::npos || what.find('\r') != std::string::npos)
      return "message is not one line: " + what.substr(0, 500);
  } catch (const std::exception& e) {
    return std::string("not a usage error: ") + e.what();
  }
  return "";
}

}  // namespace

int main(int argc, char** argv) {
  if (argc < 2) {
    std::fprintf(stderr, "usage: config_fuzz SOURCE_DIR [SECONDS] [SEED] [CASE]\n");
    return 2;
  }
  const std::filesystem::path source = argv[1];
  const double seconds = argc > 2 ? std::atof(argv[2]) : 20.0;
  const std::uint64_t seed = argc > 3 ? std::strtoull(argv[3], nullptr, 10) : 17;
  std::vector<std::string> corpus;
  for (const auto& entry : std::filesystem::directory_iterator(source / "configs"))
    if (entry.path().extension() == ".yaml") corpus.push_back(flexgait::read_text_file(entry.path()));
  corpus.push_back("a: &a\n  b: *a\n");
  corpus.push_back(
      "disturbance:\n  pushes:\n    - &p {time: 4.1, body: chest, force: [0, 120, 0], duration: 0.1}\n"
      "    - time: 5\n      body: pelvis\n      force: [1, 2, 3]\n      duration: 0.2\n    - *p\n");
  corpus.push_back("l0: &l0 {a: 1, b: 1}\nl1: &l1 {a: *l0, b: *l0}\nl2: {a: *l1, b: *l1}\n");
  flexgait::Schema schema = flexgait::rimless::rimless_analysis_schema();
  schema.merge(flexgait::schema_of<PushList>());
  if (argc > 4) {
    const std::string problem = run_case(seed, std::strtoull(argv[4], nullptr, 10), corpus, schema, true);
    std::printf("%s\n", problem.empty() ? "ok" : problem.c_str());
    return problem.empty() ? 0 : 1;
  }
  const auto t0 = std::chrono::steady_clock::now();
  std::uint64_t k = 0;
  int failures = 0;
  for (; std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count() < seconds; ++k) {
    const std::string problem = run_case(seed, k, corpus, schema, false);
    if (!problem.empty() && ++failures <= 20)
      std::printf("FAIL seed %llu case %llu: %s\n  replay: config_fuzz %s 0 %llu %llu\n",
                  static_cast<unsigned long long>(seed), static_cast<unsigned long long>(k), problem.c_str(),
                  source.c_str(), static_cast<unsigned long long>(seed), static_cast<unsigned long long>(k));
  }
  std::printf("%llu cases in %.0f s, %d failures\n", static_cast<unsigned long long>(k), seconds, failures);
  return failures == 0 ? 0 : 1;
}
