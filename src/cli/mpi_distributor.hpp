#pragma once
/// \file mpi_distributor.hpp
/// The ranks of an MPI job as a PointDistributor: the one file that calls MPI (the library stays
/// MPI-free). Rank 0 coordinates: it hands out point indices one at a time as workers ask
/// (points may differ in cost by 100x, so no static split), computes points with its own
/// threads meanwhile, and alone receives the rows and writes files. Each worker rank runs
/// `--jobs` threads (1 if the MPI library lacks MPI_THREAD_MULTIPLE), each asking for points.
#include <memory>

#include "flexgait/core/point_distributor.hpp"

namespace flexgait::cli {

/// True when this process was started by mpirun (or srun) as one of several ranks (OpenMPI's
/// OMPI_COMM_WORLD_SIZE or PMI's PMI_SIZE greater than 1).
bool launched_as_mpi_ranks();

/// Initialises MPI (finalised when the distributor goes) if launched_as_mpi_ranks(), else
/// returns nullptr (threads only). Throws UsageError if launched as ranks but built without MPI.
std::unique_ptr<PointDistributor> mpi_distributor_if_launched();

}  // namespace flexgait::cli
