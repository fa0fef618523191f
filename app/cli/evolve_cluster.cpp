#include "app/cli/evolve_cluster.hpp"

#include <cstdlib>
#include <stdexcept>
#include <string>

#if BHM_WITH_MPI
#include "app/mpi/mpi_cluster.hpp"
#endif

namespace bhm::app {

namespace {

//! The number of processes a launcher says it started (Open MPI, MPICH/Intel MPI or PMIx/Slurm),
//! 0 when none did.
int launched_world_size() {
    for (const char* name : {"OMPI_COMM_WORLD_SIZE", "PMI_SIZE", "PMIX_SIZE"})
        if (const char* v = std::getenv(name)) return std::atoi(v);
    if (std::getenv("PMIX_RANK")) return 1;  // PMIx without a size variable: ask MPI
    return 0;
}

}  // namespace

std::unique_ptr<EvolveCluster> EvolveCluster::join() {
    const int launched = launched_world_size();
#if BHM_WITH_MPI
    if (launched > 0) return make_mpi_cluster();
#else
    if (launched > 1)
        throw std::runtime_error(
            "started as one of " + std::to_string(launched) +
            " MPI processes, but this bhm was built without MPI (every process would run the "
            "whole evolution into the same directory); rebuild with libopenmpi-dev installed");
#endif
    return std::make_unique<EvolveCluster>();
}

}  // namespace bhm::app
