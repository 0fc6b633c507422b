// Run output written while the run goes (RunFiles) against the in-memory result: the same bytes,
// files that appear only when the run is done, and a result that does not grow with the run.
#include "flexgait/rimless/output.hpp"

#include <unistd.h>  // getpid: a directory of this process alone (work trees run tests at once)

#include <gtest/gtest.h>

#include <filesystem>

#include "flexgait/core/atomic_file.hpp"
#include "flexgait/rimless/flexible_wheel.hpp"
#include "flexgait/rimless/rigid_wheel.hpp"
#include "test_support.hpp"

namespace flexgait::rimless {
namespace {

using testing::measured_wheel;
using testing::run_options;

std::filesystem::path fresh_dir(const std::string& name) {
  const auto dir =
      std::filesystem::temp_directory_path() / ("flexgait_rimless_output_" + std::to_string(::getpid()) + "_" + name);
  std::filesystem::remove_all(dir);
  return dir;
}

int count_entries(const std::filesystem::path& dir) {
  int n = 0;
  for ([[maybe_unused]] const auto& e : std::filesystem::directory_iterator(dir)) ++n;
  return n;
}

SimulationResult simulate(const WheelParams& w, const SimulationOptions& o, Model model) {
  return model == Model::Rigid ? simulate_rigid(w, InitialState{}, o) : simulate_flexible(w, InitialState{}, o);
}
SimulationResult simulate(const WheelParams& w, const SimulationOptions& o, Model model, RunSink& sink) {
  return model == Model::Rigid ? simulate_rigid(w, InitialState{}, o, sink)
                               : simulate_flexible(w, InitialState{}, o, sink);
}

struct Case {
  const char* name;
  double mu;
  Model model;
  int steps;
  double sample_dt;  // [s]
};

// The streamed files are byte for byte those made from the in-memory result of the same run, and
// the summaries agree: a walking run, one long enough that every file is written in several
// pieces (log.csv > 1 MB), one that stops early (slides away: a failure event with its message),
// a jamming one (jam events) and the rigid wheel.
TEST(RunFiles, SameBytesAsTheInMemoryResult) {
  for (const Case& c : {Case{"walk", 0.6, Model::Flexible, 6, 2e-3}, Case{"pieces", 0.6, Model::Flexible, 30, 1e-4},
                        Case{"slides", 0.05, Model::Flexible, 20, 2e-3}, Case{"jams", 5.0, Model::Flexible, 5, 2e-3},
                        Case{"rigid", 0.6, Model::Rigid, 10, 2e-3}}) {
    SCOPED_TRACE(c.name);
    const WheelParams w = measured_wheel(c.mu);
    SimulationOptions o = run_options(c.steps);
    o.sample_dt = c.sample_dt;
    const SimulationResult kept = simulate(w, o, c.model);
    const auto dir = fresh_dir(c.name);
    const RunDirectory run(dir);
    RunFiles files(run);
    const SimulationResult streamed = simulate(w, o, c.model, files);
    files.finish();
    EXPECT_EQ(read_text_file(dir / "log.csv"), log_csv(kept));
    EXPECT_EQ(read_text_file(dir / "events.csv"), events_csv(kept));
    EXPECT_EQ(read_text_file(dir / "steps.csv"), steps_csv(kept));
    EXPECT_EQ(summary_json(streamed, "m"), summary_json(kept, "m"));
    EXPECT_EQ(count_entries(dir), 3);  // no temporary file left
    const std::string name = c.name;
    EXPECT_EQ(kept.failure.has_value(), name == "slides");
    EXPECT_EQ(kept.jams > 0, name == "jams");
    EXPECT_EQ(log_csv(kept).size() > (std::size_t{1} << 20), name == "pieces");
  }
}

// A run interrupted by an exception (here thrown by a sink after the 50th sample) leaves no file
// under a final name, no temporary file, and no `complete` marker.
TEST(RunFiles, InterruptedRunLeavesNoFileUnderItsFinalName) {
  const auto dir = fresh_dir("interrupted");
  int entries_while_running = -1;
  struct Interrupting final : RunSink {
    Interrupting(RunFiles& f, const std::filesystem::path& d, int& entries) : files(f), dir(d), entries(entries) {}
    void on_start(double e0) override { files.on_start(e0); }
    void on_sample(const LogSample& s) override {
      files.on_sample(s);
      if (++samples < 50) return;
      entries = count_entries(dir);
      throw std::runtime_error("interrupted");
    }
    void on_event(const EventRecord& e) override { files.on_event(e); }
    void on_step(const StepRecord& s) override { files.on_step(s); }
    RunFiles& files;
    const std::filesystem::path& dir;
    int& entries;
    int samples = 0;
  };
  auto interrupted_run = [&] {
    const RunDirectory run(dir);
    RunFiles files(run);
    Interrupting sink(files, dir, entries_while_running);
    simulate_flexible(measured_wheel(0.6), InitialState{}, run_options(5), sink);
  };
  EXPECT_THROW(interrupted_run(), std::runtime_error);
  EXPECT_EQ(entries_while_running, 3);  // the three temporary files, while the writers lived
  EXPECT_EQ(count_entries(dir), 0);
}

// A sink that only counts: what the run hands out, against what the result keeps.
struct Counting final : RunSink {
  void on_sample(const LogSample&) override { ++samples; }
  void on_event(const EventRecord&) override { ++events; }
  void on_step(const StepRecord& s) override {
    EXPECT_EQ(s.index, ++steps);  // in order, each once
  }
  long long samples = 0, events = 0;
  int steps = 0;
};

// Streaming, the result holds no sample, event or step record however long the run (memory
// O(1) in the run's length, the gait labels aside), yet its counts and summary are the
// in-memory run's.
TEST(RunFiles, StreamedResultDoesNotGrowWithTheRun) {
  const WheelParams w = measured_wheel(0.6);
  SimulationOptions o = run_options(200);
  o.sample_dt = 1e-2;
  Counting counts;
  const SimulationResult streamed = simulate_flexible(w, InitialState{}, o, counts);
  ASSERT_FALSE(streamed.failure.has_value()) << *streamed.failure;
  EXPECT_TRUE(streamed.samples.empty());
  EXPECT_TRUE(streamed.events.empty());
  EXPECT_TRUE(streamed.steps.empty());
  const SimulationResult kept = simulate_flexible(w, InitialState{}, o);
  EXPECT_EQ(counts.samples, static_cast<long long>(kept.samples.size()));
  EXPECT_EQ(counts.events, static_cast<long long>(kept.events.size()));
  EXPECT_EQ(counts.steps, static_cast<int>(kept.steps.size()));
  EXPECT_EQ(streamed.event_count, counts.events);
  EXPECT_EQ(streamed.gaits, kept.gaits);
  EXPECT_EQ(static_cast<int>(streamed.gaits.size()), streamed.steps_completed);
  EXPECT_EQ(streamed.last_step.index, kept.steps.back().index);
  EXPECT_EQ(summary_json(streamed, "m"), summary_json(kept, "m"));
}

}  // namespace
}  // namespace flexgait::rimless
