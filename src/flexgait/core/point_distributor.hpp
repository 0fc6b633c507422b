#pragma once
/// \file point_distributor.hpp
/// Who computes the independent points of a sweep or campaign: the threads of this process
/// (ThreadDistributor, oneTBB) or the ranks of an MPI job (cli/mpi_distributor.hpp). The runner
/// (sweep_runner.hpp) decides what to compute and writes the files; a distributor only spreads
/// point indices over workers and brings the rows back to the one process that writes.
#include <functional>
#include <string>
#include <vector>

namespace flexgait {

/// Computes point i: its CSV cells (no index, no newline). Called concurrently; must be thread-safe.
using PointFunction = std::function<std::string(int)>;
/// Receives a finished point. Called one at a time, in the coordinating process only.
using PointDone = std::function<void(int, const std::string&)>;

class PointDistributor {
 public:
  virtual ~PointDistributor() = default;
  /// True in the one process that reads and writes files (MPI rank 0; always true for threads).
  virtual bool coordinator() const = 0;
  /// Coordinator: computes the points `todo` with `threads` threads here (and the other workers,
  /// if any), handing them out in `todo`'s order, and calls `done` once per point. Worker processes: compute the points
  /// the coordinator hands out until it says stop (`todo` and `done` are not used). Returns when all are done.
  virtual void run(const std::vector<int>& todo, int threads, const PointFunction& point, const PointDone& done) = 0;
};

/// The threads of this process: a oneTBB arena of `threads` threads (0: all cores), each taking
/// the next point of `todo`, in its order, when it is free (points differ in cost, so no chunking
/// and no static split).
class ThreadDistributor final : public PointDistributor {
 public:
  bool coordinator() const override { return true; }
  void run(const std::vector<int>& todo, int threads, const PointFunction& point, const PointDone& done) override;
};

}  // namespace flexgait
