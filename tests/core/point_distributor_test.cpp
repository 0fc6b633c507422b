// The threads' distributor: every point once, handed out in the order of `todo` (the runner puts
// the expensive points first), and a point that throws stops the others from taking new points.
#include "flexgait/core/point_distributor.hpp"

#include <gtest/gtest.h>

#include <atomic>
#include <chrono>
#include <mutex>
#include <set>
#include <stdexcept>
#include <thread>

namespace flexgait {
namespace {

TEST(ThreadDistributor, OneThreadComputesThePointsInTodosOrder) {
  const std::vector<int> todo{5, 0, 9, 3, 7};
  std::vector<int> computed, finished;
  ThreadDistributor threads;
  threads.run(
      todo, 1,
      [&](int i) {
        computed.push_back(i);
        return std::to_string(i);
      },
      [&](int i, const std::string& cells) {
        EXPECT_EQ(cells, std::to_string(i));
        finished.push_back(i);
      });
  EXPECT_EQ(computed, todo);
  EXPECT_EQ(finished, todo);
}

TEST(ThreadDistributor, ManyThreadsComputeEveryPointOnce) {
  std::vector<int> todo;
  for (int i = 0; i < 500; ++i) todo.push_back((i * 37) % 500);  // a permutation of 0..499
  std::atomic<int> calls{0};
  std::multiset<int> finished;
  ThreadDistributor threads;
  threads.run(
      todo, 4,
      [&](int i) {
        ++calls;
        return std::to_string(i);
      },
      [&](int i, const std::string&) { finished.insert(i); });  // `done` is called one at a time
  EXPECT_EQ(calls.load(), 500);
  EXPECT_EQ(finished.size(), 500u);
  for (int i = 0; i < 500; ++i) EXPECT_EQ(finished.count(i), 1u) << i;
}

TEST(ThreadDistributor, AThrowingPointStopsTheHandingOut) {
  std::vector<int> todo(1000);
  for (int i = 0; i < 1000; ++i) todo[static_cast<std::size_t>(i)] = i;
  std::atomic<int> calls{0};
  ThreadDistributor threads;
  EXPECT_THROW(threads.run(
                   todo, 2,
                   [&](int i) -> std::string {
                     ++calls;
                     if (i == 10) throw std::runtime_error("point 10 failed");
                     // A point takes a while, as real ones do: the other thread cannot
                     // run through the list while the failing one is descheduled
                     // between its throw and the distributor's stop (a loaded machine).
                     std::this_thread::sleep_for(std::chrono::milliseconds(1));
                     return "";
                   },
                   [](int, const std::string&) {}),
               std::runtime_error);
  // Each thread finishes the point it holds and takes no new one: far fewer than the 1000 points
  // (200 leaves the other thread ~190 ms of the failing one's descheduling).
  EXPECT_LT(calls.load(), 200);
}

}  // namespace
}  // namespace flexgait
