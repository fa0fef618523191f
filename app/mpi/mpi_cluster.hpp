#pragma once
// The MPI side of EvolveCluster (app/cli/evolve_cluster.hpp), compiled only when CMake finds MPI.
#include <memory>

#include "app/cli/evolve_cluster.hpp"

namespace bhm::app {

//! Initialises MPI (MPI_THREAD_FUNNELED: only each rank's main thread calls MPI). Throws
//! std::runtime_error when MPI cannot start or lacks that thread level.
std::unique_ptr<EvolveCluster> make_mpi_cluster();

}  // namespace bhm::app
