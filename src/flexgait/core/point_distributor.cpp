#include "flexgait/core/point_distributor.hpp"

#include <tbb/parallel_for.h>
#include <tbb/task_arena.h>

#include <atomic>
#include <mutex>

namespace flexgait {

void ThreadDistributor::run(const std::vector<int>& todo, int threads, const PointFunction& point,
                            const PointDone& done) {
  std::mutex mutex;
  std::atomic<std::size_t> next{0};
  tbb::task_arena arena(threads > 0 ? threads : tbb::this_task_arena::max_concurrency());
  // One loop per thread of the arena, each taking the next point of `todo` in its order as it
  // finishes one (dynamic assignment: the expensive points the runner put first start first,
  // and the last points to start are the cheap ones, so no thread idles long at the end).
  const int loops = arena.max_concurrency();
  std::atomic<bool> failed{false};  // a point threw: the others take no new point; parallel_for rethrows
  arena.execute([&] {
    tbb::parallel_for(
        0, loops,
        [&](int) {
          for (std::size_t k = next++; k < todo.size() && !failed; k = next++) {
            const int i = todo[k];
            try {
              const std::string cells = point(i);
              const std::lock_guard<std::mutex> lock(mutex);
              done(i, cells);
            } catch (...) {
              failed = true;
              throw;
            }
          }
        },
        tbb::simple_partitioner());
  });
}

}  // namespace flexgait
