#pragma once
// Where a calibration's batches of simulations run: the scan of the box and the Jacobian at the
// optimum (evo/calibrate/calibrator.hpp). Each x of a batch is
// simulate_track(apply_fit(experiment, parameters, x), body, track): a pure function of those
// inputs, so where and in which order a batch runs cannot change a result. The worker pool runs
// them here (ThreadTrackBatches); app/mpi/ spreads them over MPI ranks under mpirun, with the
// byte messages of evo/calibrate/track_wire.hpp. evo/ itself never links MPI.
#include <atomic>
#include <cstddef>
#include <functional>
#include <vector>

#include "evo/calibrate/fit_parameters.hpp"
#include "evo/calibrate/measured_track.hpp"
#include "evo/calibrate/track_simulation.hpp"

namespace bhm::evo {

//! What every simulation of one calibration shares.
struct TrackProblem {
    const Experiment* experiment = nullptr;  //!< before the fit (x = 0)
    const std::vector<FitParameter>* parameters = nullptr;
    const Body* framed_body = nullptr;
    const MeasuredTrack* track = nullptr;
};

//! The simulation of x in `problem`: the one function every runner computes.
SimulatedTrack simulate_track_at(const TrackProblem& problem, const std::vector<double>& x,
                                 const std::atomic<bool>* cancel);

class TrackBatches {
  public:
    virtual ~TrackBatches() = default;
    //! results (resized to xs.size())[i] = simulate_track_at(problem, xs[i], cancel);
    //! on_result(i, result) once per result as it lands, one call at a time (any thread). Throws
    //! EvaluationCancelled when cancel is raised; other exceptions (a point the body does not
    //! have, a lost rank) propagate.
    virtual void simulate(const TrackProblem& problem, const std::vector<std::vector<double>>& xs,
                          std::vector<SimulatedTrack>& results, const std::atomic<bool>* cancel,
                          const std::function<void(std::size_t, const SimulatedTrack&)>& on_result) = 0;
    //! Simulations this runner runs at once.
    virtual int concurrency() const = 0;
};

//! This process's worker pool: `threads` threads take the next x in turn.
class ThreadTrackBatches final : public TrackBatches {
  public:
    explicit ThreadTrackBatches(int threads) : threads_(threads < 1 ? 1 : threads) {}
    void simulate(const TrackProblem& problem, const std::vector<std::vector<double>>& xs,
                  std::vector<SimulatedTrack>& results, const std::atomic<bool>* cancel,
                  const std::function<void(std::size_t, const SimulatedTrack&)>& on_result) override;
    int concurrency() const override { return threads_; }

  private:
    int threads_;
};

}  // namespace bhm::evo
