#pragma once
// Rank 0's evaluator over MPI: the bodies of a batch go, one at a time, to whichever rank has a
// free simulation thread (each rank holds at most as many bodies as it has threads, and gets the
// next one as soon as it returns a result: dynamic load balancing), while rank 0's own threads
// take bodies from the same queue. Results land in the batch's slots by index, so the run is the
// same whatever the ranks, threads and timing.
//
// Failures: a rank holding bodies that sends nothing (no result, no heartbeat) for the rank
// timeout is declared lost (evo::EvaluatorLost); a rank that reports an error fails the batch with
// that error; a raised cancel flag sends Cancel to every rank and throws evo::EvaluationCancelled.
// Results of an abandoned batch that arrive later are recognised by their batch id and ignored.
// A raised pause flag holds the simulations in flight on every rank until it is lowered.
#include <atomic>
#include <chrono>
#include <optional>
#include <string>
#include <vector>

#include "app/mpi/mpi_transport.hpp"
#include "evo/evaluate/evaluator.hpp"

namespace bhm::app::mpi {

class LocalWorkers;

struct RemoteRank {
    int rank = 0;
    int threads = 1;
    std::string host;
    int in_flight = 0;  //!< bodies sent, result not yet back
    std::chrono::steady_clock::time_point last_heard;
};

class MpiEvaluator final : public evo::Evaluator {
  public:
    //! Handshake: sends Setup to ranks 1..world_size-1 and waits (up to the timeout) for each
    //! one's Hello. Throws evo::EvaluatorLost naming the ranks that did not answer.
    MpiEvaluator(int world_size, int local_threads, int requested_threads, double rank_timeout_s);
    void evaluate(const evo::EvaluationBatch& batch,
                  std::vector<evo::FitnessReport>& results) override;
    int concurrency() const override;

    const std::vector<RemoteRank>& ranks() const { return ranks_; }
    int local_threads() const { return local_threads_; }
    //! Waits a little for the last sends (Cancel, Stop) to leave; false if some did not.
    bool flush(double timeout_s) { return sends_.drain(timeout_s); }

  private:
    RemoteRank& rank_of(int source);
    //! Tells every rank to hold or resume its simulations when that changes (EvolutionRun's
    //! pause; heartbeats go on, so a paused rank is never declared lost).
    void send_pause(bool paused);
    //! Sends bodies to free threads and collects results until the batch is complete.
    void dispatch(const evo::EvaluationBatch& batch, std::uint64_t batch_id,
                  std::vector<evo::FitnessReport>& results, std::atomic<std::size_t>& next,
                  LocalWorkers& local);

    std::vector<RemoteRank> ranks_;
    int local_threads_;
    double timeout_s_;
    PendingSends sends_;
    std::uint64_t batch_id_ = 0;
    std::uint64_t rules_id_ = 0;
    std::optional<evo::Experiment> sent_rules_;
    bool ranks_paused_ = false;
};

}  // namespace bhm::app::mpi
