#pragma once
// bhm evolve (and bhm calibrate's simulations) on one process or on many MPI ranks
// (docs/cluster.md). join() initialises MPI only when a launcher (mpirun, srun) started this
// process; otherwise, and in builds without MPI, the cluster is this process alone and bhm evolve
// behaves exactly as it always has.
//
// Rank 0 runs the evolution (the only writer of the run directory, owner of the RNG and the
// checkpoints) and evaluates through evaluator(); every other rank calls serve() and simulates the
// bodies rank 0 sends it until rank 0 says stop.
#include <cstdlib>
#include <memory>
#include <string>

#include "evo/calibrate/track_batches.hpp"
#include "evo/calibrate/track_wire.hpp"
#include "evo/evaluate/evaluator.hpp"

namespace bhm::app {

struct ClusterSettings {
    int local_threads = 1;         //!< rank 0's own simulation threads (resolved)
    int requested_threads = 0;     //!< --threads as asked: each rank resolves 0 on its own node
    double rank_timeout_s = 60.0;  //!< silence after which a rank is declared lost
};

class EvolveCluster {
  public:
    //! Throws std::runtime_error when launched on several ranks by a bhm built without MPI.
    static std::unique_ptr<EvolveCluster> join();
    virtual ~EvolveCluster() = default;

    virtual int rank() const { return 0; }
    virtual int size() const { return 1; }
    //! Ranks > 0: evaluates what rank 0 sends until it says stop; returns the exit status.
    virtual int serve() { return 0; }
    //! Rank 0: an evaluator over every rank (rank 0's threads included), after a handshake with
    //! each; null for a single process (EvolutionRun then uses its own threads).
    virtual std::shared_ptr<evo::Evaluator> connect(const ClusterSettings&) { return nullptr; }
    //! bhm calibrate, ranks > 0: simulates what rank 0 sends (after its TrackSetup) until it
    //! says stop; returns the exit status.
    virtual int serve_calibration() { return 0; }
    //! bhm calibrate, rank 0: the scan's and the Jacobian's batches over every rank (rank 0's
    //! `local_threads` included), after sending each the setup; null for a single process.
    virtual std::shared_ptr<evo::TrackBatches> connect_calibration(
        int /*local_threads*/, const evo::TrackSetupMessage& /*setup*/) {
        return nullptr;
    }
    //! One line describing the ranks and their threads, for the start message.
    virtual std::string describe() const { return ""; }
    //! Rank 0 after a lost rank: ends every rank now (a hung one would never finish) with status.
    [[noreturn]] virtual void abort(int status) { std::exit(status); }
};

}  // namespace bhm::app
