#include "mpi_distributor.hpp"

#include <cstdlib>
#include <string>

#include "flexgait/core/config.hpp"

#ifdef FLEXGAIT_HAVE_MPI
#include <mpi.h>

#include <algorithm>
#include <chrono>
#include <exception>
#include <mutex>
#include <thread>
#include <vector>
#endif

namespace flexgait::cli {
namespace {

int env_int(const char* name) {
  const char* v = std::getenv(name);
  return v == nullptr ? 0 : std::atoi(v);
}

#ifdef FLEXGAIT_HAVE_MPI

// Messages (tag = the worker thread's number): worker -> 0: "INDEX\nCELLS" (INDEX -1: no result,
// the first request); 0 -> worker: one int, the next point or -1 (stop).
class MpiDistributor final : public MpiRanks {
 public:
  MpiDistributor() {
    // A campaign sends a few hundred bytes per point. OpenMPI's default choice of messaging layer
    // first probes the UCX and libfabric devices, which costs ~0.2 s at every start (a one-point
    // campaign under `mpirun -np 2`: 0.36 s, against 0.16 s with ob1). Unless the user chose a
    // layer (OMPI_MCA_pml; mpirun's `--mca pml X` sets it too), ask for ob1, OpenMPI's own
    // point-to-point layer over shared memory and TCP. Every rank does the same, so they agree.
    setenv("OMPI_MCA_pml", "ob1", /*overwrite=*/0);
    int provided = 0;
    MPI_Init_thread(nullptr, nullptr, MPI_THREAD_MULTIPLE, &provided);
    MPI_Comm_rank(MPI_COMM_WORLD, &rank_);
    MPI_Comm_size(MPI_COMM_WORLD, &size_);
    multiple_ = provided >= MPI_THREAD_MULTIPLE;
  }
  ~MpiDistributor() override { MPI_Finalize(); }
  MpiDistributor(const MpiDistributor&) = delete;
  MpiDistributor& operator=(const MpiDistributor&) = delete;

  bool coordinator() const override { return rank_ == 0; }

  std::string first_error(const std::string& mine) override {
    const int own = mine.empty() ? size_ : rank_;
    int first = size_;
    MPI_Allreduce(&own, &first, 1, MPI_INT, MPI_MIN, MPI_COMM_WORLD);
    if (first == size_) return "";
    if (rank_ != 0) {
      if (rank_ == first) MPI_Send(mine.data(), static_cast<int>(mine.size()), MPI_CHAR, 0, kErrorTag, MPI_COMM_WORLD);
      return mine.empty() ? "rank " + std::to_string(first) + " failed (reported by rank 0)" : mine;
    }
    if (first == 0) return mine;
    MPI_Status status;
    MPI_Probe(first, kErrorTag, MPI_COMM_WORLD, &status);
    int bytes = 0;
    MPI_Get_count(&status, MPI_CHAR, &bytes);
    std::string message(static_cast<std::size_t>(bytes), '\0');
    MPI_Recv(message.data(), bytes, MPI_CHAR, first, kErrorTag, MPI_COMM_WORLD, MPI_STATUS_IGNORE);
    return "rank " + std::to_string(first) + ": " + message;
  }

  void run(const std::vector<int>& todo, int threads, const PointFunction& point, const PointDone& done) override {
    const int local = threads > 0 ? threads : 1;
    const int per_worker = multiple_ ? local : 1;
    if (rank_ != 0) {
      std::vector<std::thread> pool;
      for (int t = 1; t < per_worker; ++t) pool.emplace_back([&, t] { work(t, point); });
      work(0, point);
      for (auto& th : pool) th.join();
      return;
    }
    coordinate(todo, local, (size_ - 1) * per_worker * kPointsInHand, point, done);
  }

 private:
  // A worker thread keeps kPointsInHand requests outstanding: the reply to the message that
  // carries one point's result (and asks for another) arrives while it computes the next point,
  // so it never waits for rank 0's polling (which sleeps up to 1 ms between looks). Replies
  // come in the order of the requests (MPI's non-overtaking rule for one source, tag and
  // communicator); once the queue is empty every reply is -1, so a thread receives exactly
  // kPointsInHand of them.
  static void work(int tag, const PointFunction& point) {
    const auto send = [tag](const std::string& message) {
      MPI_Send(message.data(), static_cast<int>(message.size()), MPI_CHAR, 0, tag, MPI_COMM_WORLD);
    };
    for (int k = 0; k < kPointsInHand; ++k) send("-1\n");
    for (int outstanding = kPointsInHand; outstanding > 0; --outstanding) {
      int i = -1;
      MPI_Recv(&i, 1, MPI_INT, 0, tag, MPI_COMM_WORLD, MPI_STATUS_IGNORE);
      if (i < 0) continue;  // the queue is empty: collect the remaining -1 replies
      send(std::to_string(i) + "\n" + point(i));
      ++outstanding;
    }
  }

  // Rank 0: `local` threads compute here while this thread answers the workers' threads until
  // each has had its kPointsInHand replies -1 (`requesters` counts those still due); all take
  // the next point from one queue.
  static void coordinate(const std::vector<int>& todo, int local, int requesters, const PointFunction& point,
                         const PointDone& done) {
    std::mutex queue_mutex, done_mutex;
    std::size_t next = 0;
    auto take = [&] {
      const std::lock_guard<std::mutex> lock(queue_mutex);
      return next < todo.size() ? todo[next++] : -1;
    };
    auto finish = [&](int i, const std::string& cells) {
      const std::lock_guard<std::mutex> lock(done_mutex);
      done(i, cells);
    };
    std::exception_ptr failure;
    std::vector<std::thread> pool;
    for (int t = 0; t < local; ++t)
      pool.emplace_back([&] {
        try {
          for (int i = take(); i >= 0; i = take()) finish(i, point(i));
        } catch (...) {
          const std::lock_guard<std::mutex> lock(done_mutex);
          if (!failure) failure = std::current_exception();
        }
      });
    // Idle, this thread sleeps between polls (a blocking MPI receive would spin on the core that
    // rank 0's own point threads share), the sleep doubling from 20 us to 1 ms while nothing
    // comes: at most ~1000 wake-ups a second. The workers do not wait for the answer (their
    // next point is already in hand), unless a point takes less than that delay.
    auto idle = std::chrono::microseconds(20);
    while (requesters > 0) {
      int arrived = 0;
      MPI_Status status;
      MPI_Iprobe(MPI_ANY_SOURCE, MPI_ANY_TAG, MPI_COMM_WORLD, &arrived, &status);
      if (arrived == 0) {
        std::this_thread::sleep_for(idle);
        idle = std::min(2 * idle, std::chrono::microseconds(1000));
        continue;
      }
      idle = std::chrono::microseconds(20);
      int bytes = 0;
      MPI_Get_count(&status, MPI_CHAR, &bytes);
      std::string message(static_cast<std::size_t>(bytes), '\0');
      MPI_Recv(message.data(), bytes, MPI_CHAR, status.MPI_SOURCE, status.MPI_TAG, MPI_COMM_WORLD, MPI_STATUS_IGNORE);
      const auto newline = message.find('\n');
      const int i = std::stoi(message.substr(0, newline));
      if (i >= 0) finish(i, message.substr(newline + 1));
      const int reply = take();
      MPI_Send(&reply, 1, MPI_INT, status.MPI_SOURCE, status.MPI_TAG, MPI_COMM_WORLD);
      if (reply < 0) --requesters;
    }
    for (auto& th : pool) th.join();
    if (failure) std::rethrow_exception(failure);
  }

  static constexpr int kPointsInHand = 2;  // the point computed and the next one
  static constexpr int kErrorTag = 32767;  // MPI_TAG_UB is at least this; worker threads use 0 .. 1023
  int rank_ = 0, size_ = 1;
  bool multiple_ = false;
};

#endif

}  // namespace

bool launched_as_mpi_ranks() {
  return env_int("OMPI_COMM_WORLD_SIZE") > 1 || env_int("PMI_SIZE") > 1;
}

bool secondary_mpi_rank() {
  return launched_as_mpi_ranks() && (env_int("OMPI_COMM_WORLD_RANK") > 0 || env_int("PMI_RANK") > 0);
}

std::unique_ptr<MpiRanks> mpi_distributor_if_launched() {
  if (!launched_as_mpi_ranks()) return nullptr;
#ifdef FLEXGAIT_HAVE_MPI
  return std::make_unique<MpiDistributor>();
#else
  throw UsageError(
      "started as several MPI ranks, but this flexgait was built without MPI (install libopenmpi-dev and "
      "rebuild, or run without mpirun: the threads of one machine, --jobs)");
#endif
}

}  // namespace flexgait::cli
