#pragma once
// bhm calibrate under mpirun (docs/calibration.md, docs/cluster.md): the calibration's batches of
// simulations (the scan of the box, the Jacobian) spread over the ranks. Rank 0 runs the fit
// (evo::calibrate) and hands each batch to MpiTrackBatches, which sends every other rank jobs (x
// vectors) while rank 0's own threads take jobs from the same queue; ranks > 0 run
// serve_track_batches. Results go back into their slots by index and travel bit for bit
// (evo/calibrate/track_wire.hpp), so the fit equals the single-process one whatever the ranks.
// Only each rank's main thread calls MPI (MPI_THREAD_FUNNELED).
#include <memory>
#include <string>
#include <vector>

#include "evo/calibrate/track_batches.hpp"
#include "evo/calibrate/track_wire.hpp"

namespace bhm::app::mpi {

class MpiTrackBatches final : public evo::TrackBatches {
  public:
    //! Sends the setup to ranks 1..size-1 and waits for each one's Hello (threads, host).
    //! Throws std::runtime_error naming a rank that failed or stayed silent for timeout_s.
    MpiTrackBatches(int size, int local_threads, const evo::TrackSetupMessage& setup,
                    double timeout_s);
    ~MpiTrackBatches() override;
    void simulate(const evo::TrackProblem& problem, const std::vector<std::vector<double>>& xs,
                  std::vector<evo::SimulatedTrack>& results, const std::atomic<bool>* cancel,
                  const std::function<void(std::size_t, const evo::SimulatedTrack&)>& on_result)
        override;
    int concurrency() const override;
    //! "2 MPI ranks, 4 simulation threads: rank 0 (2), 1 on node17 (2)"
    std::string describe(const std::string& host) const;

  private:
    struct Rank {
        int rank = 0;
        int threads = 1;
        std::string host;
    };
    int local_threads_ = 1;
    std::vector<Rank> ranks_;
    std::uint64_t batch_ = 0;
};

//! Ranks > 0: waits for the setup, answers Hello, simulates every job on its threads and sends
//! the results until rank 0 says stop. Returns the exit status.
int serve_track_batches(int rank, const std::string& host);

}  // namespace bhm::app::mpi
