#include "flexgait/core/point_distributor.hpp"

#include <tbb/parallel_for.h>
#include <tbb/task_arena.h>

#include <mutex>

namespace flexgait {

void ThreadDistributor::run(const std::vector<int>& todo, int threads, const PointFunction& point,
                            const PointDone& done) {
  std::mutex mutex;
  tbb::task_arena arena(threads > 0 ? threads : tbb::this_task_arena::max_concurrency());
  arena.execute([&] {
    tbb::parallel_for(
        tbb::blocked_range<std::size_t>(0, todo.size(), 1),
        [&](const tbb::blocked_range<std::size_t>& range) {
          for (std::size_t k = range.begin(); k != range.end(); ++k) {
            const int i = todo[k];
            const std::string cells = point(i);
            const std::lock_guard<std::mutex> lock(mutex);
            done(i, cells);
          }
        },
        tbb::simple_partitioner());
  });
}

}  // namespace flexgait
