// The sweep runner: an interrupted sweep, resumed, gives the same file as one run through.
#include "flexgait/core/sweep_runner.hpp"

#include <unistd.h>  // getpid: a directory of this process alone (work trees run tests at once)

#include <gtest/gtest.h>

#include <atomic>
#include <filesystem>

#include "flexgait/core/atomic_file.hpp"

namespace flexgait {
namespace {

SweepJob job(const std::filesystem::path& dir) {
  SweepJob j;
  j.dir = dir;
  j.header = "value,square";
  j.count = 40;
  j.jobs = 2;
  j.signature = "squares 0..39";
  j.row = [](int i) { return std::to_string(i) + "," + std::to_string(i * i); };
  return j;
}

TEST(SweepRunner, InterruptedAndResumedEqualsOneRunThrough) {
  const auto base = std::filesystem::temp_directory_path() / ("flexgait_sweep_test_" + std::to_string(::getpid()));
  std::filesystem::remove_all(base);
  const SweepOutcome whole = run_sweep(job(base / "whole"));
  EXPECT_EQ(whole.computed, 40);

  SweepJob broken = job(base / "killed");
  std::atomic<int> calls{0};
  broken.row = [&calls](int i) {
    if (++calls > 15) throw std::runtime_error("interrupted");
    return std::to_string(i) + "," + std::to_string(i * i);
  };
  EXPECT_THROW(run_sweep(broken), std::runtime_error);
  EXPECT_FALSE(std::filesystem::exists(base / "killed" / "sweep.csv"));
  // A write torn by the interruption: a last line without its newline.
  append_file_durable(base / "killed" / "sweep.partial.csv", "39,39,15");

  SweepJob again = job(base / "killed");
  again.resume = true;
  const SweepOutcome resumed = run_sweep(again);
  EXPECT_GE(resumed.resumed, 10);
  EXPECT_EQ(resumed.resumed + resumed.computed, 40);
  EXPECT_EQ(read_text_file(base / "killed" / "sweep.csv"), read_text_file(base / "whole" / "sweep.csv"));

  SweepJob other = job(base / "killed");
  other.resume = true;
  other.signature = "another sweep";
  EXPECT_THROW(run_sweep(other), UsageError);
}

// --resume once trusted any line of the partial file; a garbage row reached the final CSV.
TEST(SweepRunner, ResumeKeepsOnlyValidRows) {
  const auto base =
      std::filesystem::temp_directory_path() / ("flexgait_sweep_garbage_test_" + std::to_string(::getpid()));
  std::filesystem::remove_all(base);
  const SweepOutcome whole = run_sweep(job(base / "whole"));
  SweepJob again = job(base / "whole");
  again.resume = true;
  // Valid rows for 0 and 1, then lines that are not finished points of this sweep.
  write_file_atomic(base / "whole" / "sweep.partial.csv",
                    "0,0,0\n1,1,1\n2,garbage\n3x,3,9\n-4,4,16\n+5,5,25\n40,40,1600\n1,1,2\n6,6,36,extra\n"
                    "\"7\",7,49\n,8,64\n999999999999,9,81\n");
  const SweepOutcome resumed = run_sweep(again);
  EXPECT_EQ(resumed.resumed, 2);
  EXPECT_EQ(resumed.computed, 38);
  EXPECT_EQ(read_text_file(base / "whole" / "sweep.csv"), [&] {
    std::string text = "index,value,square\n";
    for (int i = 0; i < 40; ++i)
      text += std::to_string(i) + "," + std::to_string(i) + "," + std::to_string(i * i) + "\n";
    return text;
  }());
  (void)whole;
}

// Rows with the right cell count and garbage values: the job's valid_row refuses them; the
// messages use the job's noun.
TEST(SweepRunner, ResumeAsksTheJobWhetherARowsCellsAreItsOwn) {
  const auto base =
      std::filesystem::temp_directory_path() / ("flexgait_sweep_cells_test_" + std::to_string(::getpid()));
  std::filesystem::remove_all(base);
  SweepJob first = job(base / "c");
  first.noun = "campaign";
  run_sweep(first);
  SweepJob again = first;
  again.resume = true;
  again.valid_row = [](int i, const std::vector<std::string>& cells) {
    return cells.size() == 2 && cells[0] == std::to_string(i) &&
           cells[1].find_first_not_of("0123456789") == std::string::npos;
  };
  write_file_atomic(base / "c" / "sweep.partial.csv", "0,0,0\n1,1,x\n2,7,4\n3,3,9\n");
  const SweepOutcome resumed = run_sweep(again);
  EXPECT_EQ(resumed.resumed, 2);  // 0 and 3
  EXPECT_EQ(resumed.computed, 38);
  std::string expected = "index,value,square\n";
  for (int i = 0; i < 40; ++i)
    expected += std::to_string(i) + "," + std::to_string(i) + "," + std::to_string(i * i) + "\n";
  EXPECT_EQ(read_text_file(base / "c" / "sweep.csv"), expected);
  SweepJob none = job(base / "empty");
  none.noun = "campaign";
  none.resume = true;
  try {
    check_resumable(none);
    FAIL() << "resumed nothing";
  } catch (const UsageError& e) {
    EXPECT_EQ(std::string(e.what()), "--resume: no campaign to resume in " + (base / "empty").string());
  }
  // An --out that is a regular file: bad usage (exit 2), nothing written.
  write_file_atomic(base / "a_file", "x");
  EXPECT_THROW(run_sweep(job(base / "a_file")), UsageError);
  EXPECT_EQ(read_text_file(base / "a_file"), "x");
}

// A distributor standing in for MPI: as coordinator it computes the points in reverse order (the
// order rows arrive from workers is arbitrary); as a worker it only records that it ran.
class ReverseDistributor final : public PointDistributor {
 public:
  explicit ReverseDistributor(bool coordinator) : coordinator_(coordinator) {}
  bool coordinator() const override { return coordinator_; }
  void run(const std::vector<int>& todo, int, const PointFunction& point, const PointDone& done) override {
    ++runs;
    handed = todo.size();
    for (auto it = todo.rbegin(); it != todo.rend(); ++it) done(*it, point(*it));
  }
  int runs = 0;
  std::size_t handed = 0;

 private:
  bool coordinator_;
};

TEST(SweepRunner, AnyDistributorGivesTheSameFile) {
  const auto base =
      std::filesystem::temp_directory_path() / ("flexgait_sweep_distributor_test_" + std::to_string(::getpid()));
  std::filesystem::remove_all(base);
  run_sweep(job(base / "threads"));
  SweepJob reversed = job(base / "reversed");
  ReverseDistributor coordinator(true);
  reversed.distributor = &coordinator;
  run_sweep(reversed);
  EXPECT_EQ(read_text_file(base / "threads" / "sweep.csv"), read_text_file(base / "reversed" / "sweep.csv"));
  std::filesystem::remove_all(base);
}

// Records the order the runner hands the points out in, and computes them in that order.
class RecordingDistributor final : public PointDistributor {
 public:
  bool coordinator() const override { return true; }
  void run(const std::vector<int>& todo, int, const PointFunction& point, const PointDone& done) override {
    order = todo;
    for (const int i : todo) done(i, point(i));
  }
  std::vector<int> order;
};

TEST(SweepRunner, HandsOutTheMostExpensivePointsFirstAndWritesByIndex) {
  const auto base = std::filesystem::temp_directory_path() / ("flexgait_sweep_cost_test_" + std::to_string(::getpid()));
  std::filesystem::remove_all(base);
  run_sweep(job(base / "plain"));
  SweepJob costly = job(base / "costly");
  costly.cost = [](int i) { return static_cast<double>(i % 3); };
  RecordingDistributor recorder;
  costly.distributor = &recorder;
  run_sweep(costly);
  ASSERT_EQ(recorder.order.size(), 40u);
  for (std::size_t k = 1; k < recorder.order.size(); ++k) {  // cost descending, ties by index
    const int a = recorder.order[k - 1], b = recorder.order[k];
    EXPECT_TRUE(a % 3 > b % 3 || (a % 3 == b % 3 && a < b)) << a << " before " << b;
  }
  EXPECT_EQ(read_text_file(base / "plain" / "sweep.csv"), read_text_file(base / "costly" / "sweep.csv"));
  std::filesystem::remove_all(base);
}

TEST(SweepRunner, AWorkerWritesNothingAndAFailedResumeReleasesTheWorkers) {
  const auto base =
      std::filesystem::temp_directory_path() / ("flexgait_sweep_worker_test_" + std::to_string(::getpid()));
  std::filesystem::remove_all(base);
  SweepJob worker_job = job(base / "worker");
  ReverseDistributor worker(false);
  worker_job.distributor = &worker;
  run_sweep(worker_job);
  EXPECT_EQ(worker.runs, 1);
  EXPECT_FALSE(std::filesystem::exists(base / "worker"));

  SweepJob resume = job(base / "none");
  resume.resume = true;
  ReverseDistributor coordinator(true);
  resume.distributor = &coordinator;
  EXPECT_THROW(run_sweep(resume), UsageError);
  EXPECT_EQ(coordinator.runs, 1);  // called once with nothing to do: the workers are told to stop
  EXPECT_EQ(coordinator.handed, 0u);
  EXPECT_FALSE(std::filesystem::exists(base / "none"));
}

}  // namespace
}  // namespace flexgait
