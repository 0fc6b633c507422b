#include "flexgait/core/sweep_runner.hpp"

#include <fmt/format.h>
#include <tbb/global_control.h>
#include <tbb/parallel_for.h>
#include <tbb/task_arena.h>

#include <chrono>
#include <map>
#include <mutex>
#include <stdexcept>

#include "flexgait/core/atomic_file.hpp"
#include "flexgait/core/text.hpp"
#include "flexgait/core/progress.hpp"

namespace flexgait {
namespace {

// Finished rows of a partial file: complete CSV records "index,cells"; a torn last record is dropped.
std::map<int, std::string> read_partial(const std::filesystem::path& p, int count) {
  std::map<int, std::string> rows;
  for (const CsvRecord& record : parse_csv(read_text_file(p))) {
    const std::size_t comma = record.text.find(',');
    if (comma == std::string::npos) continue;
    try {
      const int i = std::stoi(record.text.substr(0, comma));
      if (i >= 0 && i < count) rows[i] = record.text.substr(comma + 1);
    } catch (const std::exception&) {
    }
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
  if (job.resume) rows = read_partial(partial, job.count);
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
