#include "flexgait/core/sweep_runner.hpp"

#include <fmt/format.h>
#include <tbb/global_control.h>
#include <tbb/parallel_for.h>
#include <tbb/task_arena.h>

#include <charconv>
#include <chrono>
#include <map>
#include <mutex>
#include <stdexcept>

#include "flexgait/core/atomic_file.hpp"
#include "flexgait/core/text.hpp"
#include "flexgait/core/progress.hpp"

namespace flexgait {
namespace {

// Finished rows of a partial file: complete CSV records "index,cells" with an index in [0, count)
// written in full (digits only) and as many fields as the header has columns. Anything else (a torn
// last record, a line that is not the sweep's) is left out, to be computed again; *rejected counts it.
std::map<int, std::string> read_partial(const std::filesystem::path& p, const SweepJob& job, int* rejected) {
  const std::size_t columns = parse_csv(job.header + "\n").front().fields.size() + 1;
  std::map<int, std::string> rows;
  *rejected = 0;
  for (const CsvRecord& record : parse_csv(read_text_file(p))) {
    const std::string& index = record.fields.front();
    int i = -1;
    const auto [end, ec] = std::from_chars(index.data(), index.data() + index.size(), i);
    const bool valid = record.fields.size() == columns && !index.empty() && index.front() != '-' &&
                       ec == std::errc() && end == index.data() + index.size() && i < job.count &&
                       record.text.rfind(index + ",", 0) == 0 && rows.count(i) == 0;
    if (valid) rows[i] = record.text.substr(index.size() + 1);
    else ++*rejected;
  }
  return rows;
}

}  // namespace

void check_resumable(const SweepJob& job) {
  if (!job.resume) return;
  const auto signature = job.dir / (job.name + ".signature");
  if (!std::filesystem::exists(signature))
    throw UsageError(fmt::format("--resume: no sweep to resume in {}", job.dir.string()));
  if (read_text_file(signature) != job.signature)
    throw UsageError(fmt::format("--resume: {} holds a different sweep (see {})", job.dir.string(),
                                            signature.string()));
}

SweepOutcome run_sweep(const SweepJob& job) {
  check_resumable(job);
  std::filesystem::create_directories(job.dir);
  const auto partial = job.dir / (job.name + ".partial.csv");
  const auto signature = job.dir / (job.name + ".signature");
  const auto final_csv = job.dir / (job.name + ".csv");
  std::map<int, std::string> rows;
  if (job.resume) {
    int rejected = 0;
    rows = read_partial(partial, job, &rejected);
    if (rejected > 0)
      fmt::print(stderr, "note: --resume: {} line(s) of {} are not finished points of this sweep; computed again\n",
                 rejected, partial.string());
  }
  if (!job.resume) std::filesystem::remove(partial);
  write_file_atomic(signature, job.signature);
  // Rewrite the partial file with only complete rows, so a torn line does not linger.
  {
    std::string text;
    for (const auto& [i, cells] : rows) text += fmt::format("{},{}\n", i, cells);
    write_file_atomic(partial, text);
  }
  SweepOutcome out;
  out.resumed = static_cast<int>(rows.size());
  std::vector<int> todo;
  for (int i = 0; i < job.count; ++i)
    if (!rows.count(i)) todo.push_back(i);

  const auto t0 = std::chrono::steady_clock::now();
  std::mutex mutex;
  ProgressBar progress(job.count, "points", out.resumed);
  progress.show(out.resumed);
  const int threads = job.jobs > 0 ? job.jobs : tbb::this_task_arena::max_concurrency();
  tbb::task_arena arena(threads);
  arena.execute([&] {
    tbb::parallel_for(
        tbb::blocked_range<std::size_t>(0, todo.size(), 1),
        [&](const tbb::blocked_range<std::size_t>& range) {
          for (std::size_t k = range.begin(); k != range.end(); ++k) {
            const int i = todo[k];
            const std::string cells = job.row(i);
            const std::lock_guard<std::mutex> lock(mutex);
            append_file_durable(partial, fmt::format("{},{}\n", i, cells));
            rows[i] = cells;
            ++out.computed;
            progress.show(out.resumed + out.computed);
          }
        },
        tbb::simple_partitioner());
  });
  std::string text = "index," + job.header + "\n";
  for (const auto& [i, cells] : rows) text += fmt::format("{},{}\n", i, cells);
  write_file_atomic(final_csv, text);
  out.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
  return out;
}

}  // namespace flexgait
