#pragma once
// Ranks > 0 of `mpirun bhm evolve`: simulate the bodies rank 0 sends until it says stop. The main
// thread does all the MPI (receives, result sends, a heartbeat every second); `--threads` worker
// threads simulate. A Cancel for a batch stops its running simulations at their next sample and
// drops its queued bodies; Pause holds the running ones where they are until rank 0 resumes.
//
// For the failure tests only: BHM_MPI_TEST_FAULT="RANK:BATCH:hang" makes rank RANK stop answering
// (no results, no heartbeats) instead of sending its first result of batch BATCH (batch 1 is the
// session's first generation that simulates anything); ":exit" makes it exit(1) there instead,
// ":fail" makes it report an error there instead of that result (and go on serving).
#include <string>

namespace bhm::app::mpi {

//! Returns the exit status of this rank.
int serve_evaluations(int rank, const std::string& host);

}  // namespace bhm::app::mpi
