#pragma once
/// \file mpi_distributor.hpp
/// The ranks of an MPI job as a PointDistributor: the one file that calls MPI (the library stays
/// MPI-free). Rank 0 coordinates: it hands out point indices one at a time as workers ask
/// (points may differ in cost by 100x, so no static split), computes points with its own
/// threads meanwhile, and alone receives the rows and writes files. Each worker rank runs
/// `--jobs` threads (1 if the MPI library lacks MPI_THREAD_MULTIPLE), each asking for points.
#include <memory>
#include <string>

#include "flexgait/core/point_distributor.hpp"

namespace flexgait::cli {

/// The ranks of an MPI job (MPI initialised while it lives).
class MpiRanks : public PointDistributor {
 public:
  /// Collective (every rank calls it once, before run): `mine` is this rank's error ("" for
  /// none). Returns "" if no rank has one. Otherwise, on rank 0, the error of the lowest rank
  /// that has one (prefixed "rank R: " if R is not 0), so rank 0 can report it once; on the
  /// other ranks a non-empty text (their own error, if any) that they need not print.
  virtual std::string first_error(const std::string& mine) = 0;
};

/// True when this process was started by mpirun (or srun) as one of several ranks (OpenMPI's
/// OMPI_COMM_WORLD_SIZE or PMI's PMI_SIZE greater than 1).
bool launched_as_mpi_ranks();

/// True in a rank other than 0 of such a job (OMPI_COMM_WORLD_RANK or PMI_RANK, read without
/// MPI): it leaves the report of an error every rank shares, such as a bad argument, to rank 0.
bool secondary_mpi_rank();

/// Initialises MPI (finalised when the distributor goes) if launched_as_mpi_ranks(), else
/// returns nullptr (threads only). Throws UsageError if launched as ranks but built without MPI.
std::unique_ptr<MpiRanks> mpi_distributor_if_launched();

}  // namespace flexgait::cli
