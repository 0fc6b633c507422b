#include "flexgait/core/sweep_runner.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <charconv>
#include <chrono>
#include <condition_variable>
#include <exception>
#include <map>
#include <mutex>
#include <stdexcept>
#include <thread>

#include "flexgait/core/atomic_file.hpp"
#include "flexgait/core/progress.hpp"
#include "flexgait/core/run_directory.hpp"
#include "flexgait/core/text.hpp"

namespace flexgait {
namespace {

// Finished rows of a partial file: complete CSV records "index,cells" with an index in [0, count)
// written in full (digits only), as many fields as the header has columns, and cells the job's
// valid_row accepts. Anything else (a torn last record, a line that is not the sweep's, garbage
// in a cell) is left out, to be computed again; *rejected counts it. Records are read one at a
// time with at most columns + 1 fields kept: memory is the file's text and the rows kept.
std::map<int, std::string> read_partial(const std::filesystem::path& p, const SweepJob& job, int* rejected) {
  const std::size_t columns = parse_csv(job.header + "\n").front().fields.size() + 1;
  std::map<int, std::string> rows;
  *rejected = 0;
  std::vector<std::string> cells;
  for_each_csv_record(
      read_text_file(p),
      [&](CsvRecord& record) {
        const std::string& index = record.fields.front();
        int i = -1;
        const auto [end, ec] = std::from_chars(index.data(), index.data() + index.size(), i);
        bool valid = record.fields.size() == columns && !index.empty() && index.front() != '-' && ec == std::errc() &&
                     end == index.data() + index.size() && i < job.count && record.text.rfind(index + ",", 0) == 0 &&
                     rows.count(i) == 0;
        if (valid && job.valid_row) {
          cells.assign(std::make_move_iterator(record.fields.begin() + 1),
                       std::make_move_iterator(record.fields.end()));
          valid = job.valid_row(i, cells);
        }
        if (valid)
          rows[i] = record.text.substr(index.size() + 1);
        else
          ++*rejected;
      },
      columns);
  return rows;
}

// Appends finished rows to the partial file from a thread of its own: each wake-up writes every
// row that has come since the last one and flushes them to disk together (fsync). The points'
// threads never wait for the disk: a flush costs 1-100 ms on a busy disk, more than a cheap point.
class DurableAppender {
 public:
  explicit DurableAppender(std::filesystem::path path) : path_(std::move(path)) {}
  ~DurableAppender() { stop(); }
  DurableAppender(const DurableAppender&) = delete;
  DurableAppender& operator=(const DurableAppender&) = delete;

  void add(const std::string& line) {
    {
      const std::lock_guard<std::mutex> lock(mutex_);
      pending_ += line;
    }
    wake_.notify_one();
  }
  /// Writes what is pending, stops the thread; rethrows a write's failure.
  void finish() {
    stop();
    if (failure_) std::rethrow_exception(failure_);
  }

 private:
  void stop() {
    {
      const std::lock_guard<std::mutex> lock(mutex_);
      stopping_ = true;
    }
    wake_.notify_one();
    if (thread_.joinable()) thread_.join();
  }
  void loop() {
    for (;;) {
      std::string batch;
      {
        std::unique_lock<std::mutex> lock(mutex_);
        wake_.wait(lock, [&] { return stopping_ || !pending_.empty(); });
        if (pending_.empty()) return;  // stopping, nothing left
        batch.swap(pending_);
      }
      try {
        if (!failure_) append_file_durable(path_, batch);
      } catch (...) {
        failure_ = std::current_exception();
      }
    }
  }

  std::filesystem::path path_;
  std::mutex mutex_;
  std::condition_variable wake_;
  std::string pending_;
  bool stopping_ = false;
  std::exception_ptr failure_;              // written by the thread only, read after it is joined
  std::thread thread_{[this] { loop(); }};  // last: starts once the members above exist
};

}  // namespace

void check_resumable(const SweepJob& job) {
  if (!job.resume) return;
  const auto signature = job.dir / (job.name + ".signature");
  if (!std::filesystem::exists(signature))
    throw UsageError(fmt::format("--resume: no {} to resume in {}", job.noun, one_line(job.dir.string(), 1000)));
  if (read_text_file(signature) != job.signature)
    throw UsageError(fmt::format("--resume: {} holds a different {} (see {})", one_line(job.dir.string(), 1000),
                                 job.noun, one_line(signature.string(), 1000)));
}

namespace {

SweepOutcome run_coordinator(const SweepJob& job, PointDistributor& distributor) {
  std::map<int, std::string> rows;
  std::vector<int> todo;
  try {
    check_resumable(job);
    make_output_directory(job.dir);
    if (job.prepare) job.prepare();
  } catch (...) {
    distributor.run({}, 0, job.row, {});  // release the workers, then report
    throw;
  }
  const auto partial = job.dir / (job.name + ".partial.csv");
  const auto signature = job.dir / (job.name + ".signature");
  const auto final_csv = job.dir / (job.name + ".csv");
  if (job.resume) {
    int rejected = 0;
    rows = read_partial(partial, job, &rejected);
    if (rejected > 0)
      fmt::print(stderr, "note: --resume: {} line(s) of {} are not finished points of this {}; computed again\n",
                 rejected, partial.string(), job.noun);
  }
  if (!job.resume) std::filesystem::remove(partial);
  // Durable, as the appended rows: a resume after a power cut trusts both.
  write_file_durable(signature, job.signature);
  // Rewrite the partial file with only complete rows, so a torn line does not linger.
  {
    std::string text;
    for (const auto& [i, cells] : rows) text += fmt::format("{},{}\n", i, cells);
    write_file_durable(partial, text);
  }
  SweepOutcome out;
  out.resumed = static_cast<int>(rows.size());
  for (int i = 0; i < job.count; ++i)
    if (!rows.count(i)) todo.push_back(i);
  if (job.cost) {  // most expensive first (dynamic assignment then ends on the cheap points)
    std::vector<double> cost(static_cast<std::size_t>(job.count), 0.0);
    for (const int i : todo) cost[static_cast<std::size_t>(i)] = job.cost(i);
    std::stable_sort(todo.begin(), todo.end(), [&](int a, int b) {
      return cost[static_cast<std::size_t>(a)] > cost[static_cast<std::size_t>(b)];
    });
  }

  const auto t0 = std::chrono::steady_clock::now();
  ProgressBar progress(job.count, "points", out.resumed, true);
  progress.show(out.resumed);
  DurableAppender appender(partial);
  distributor.run(todo, job.jobs, job.row, [&](int i, const std::string& cells) {
    appender.add(fmt::format("{},{}\n", i, cells));
    rows[i] = cells;
    ++out.computed;
    progress.show(out.resumed + out.computed);
  });
  appender.finish();
  std::string text = sweep_file_header(job.header) + "\n";
  for (const auto& [i, cells] : rows) text += fmt::format("{},{}\n", i, cells);
  write_file_atomic(final_csv, text);
  out.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
  return out;
}

}  // namespace

SweepOutcome run_sweep(const SweepJob& job) {
  ThreadDistributor threads;
  PointDistributor& distributor = job.distributor != nullptr ? *job.distributor : threads;
  if (!distributor.coordinator()) {  // an MPI worker: compute what rank 0 hands out, write nothing
    const auto t0 = std::chrono::steady_clock::now();
    distributor.run({}, job.jobs, job.row, {});
    SweepOutcome out;
    out.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
    return out;
  }
  return run_coordinator(job, distributor);
}

}  // namespace flexgait
