#pragma once
// bhm calibrate's fit: the parameters (evo/calibrate/fit_parameters.hpp) that minimise the misfit
// between a measured track and the simulated one (evo/calibrate/track_simulation.hpp), found by
// NLopt's BOBYQA (Powell 2009: bounded, derivative-free, a quadratic model of the misfit) in log
// space, after a parallel scan of the box on the worker pool, polished by Gauss-Newton steps
// (evo/calibrate/gauss_newton_polish.hpp); then the uncertainty and identifiability from the
// Jacobian of the residuals at the optimum (evo/calibrate/identifiability.hpp), its 2p
// simulations run at once on the worker pool.
#include <atomic>
#include <functional>
#include <memory>
#include <string>
#include <vector>

#include "evo/calibrate/fit_parameters.hpp"
#include "evo/calibrate/identifiability.hpp"
#include "evo/calibrate/measured_track.hpp"
#include "evo/calibrate/track_batches.hpp"
#include "evo/calibrate/track_simulation.hpp"

namespace bhm::evo {

//! False where bhm was built without NLopt: calibrate() then throws.
bool calibration_available();

struct CalibrationOptions {
    int threads = 0;             //!< worker threads for the Jacobian (0 = all)
    //! Budget of the scan's, BOBYQA's and the Gauss-Newton polish's simulations; the polish gets
    //! what BOBYQA leaves unused (no reserve: calibrator.cpp).
    int max_simulations = 200;
    double x_tolerance = 1e-4;   //!< stop once a step changes no x by more (log units)
    double jacobian_step = 0.01; //!< central-difference step in x
    //! A misfit below this fraction of the track's motion RMS counts as a good fit.
    double good_fit_fraction = 0.2;
    //! Raised (a UI's Cancel): the fit throws EvaluationCancelled within one track row's
    //! simulation.
    const std::atomic<bool>* cancel = nullptr;
    //! After each simulation of the scan and the optimiser: how many so far and the best misfit
    //! (metres). Called by one thread at a time, which may be a worker of the pool.
    std::function<void(int simulations, double best_misfit_m)> progress;
    //! Where the scan's and the Jacobian's batches run (MPI ranks under mpirun, app/mpi/); null:
    //! this process's worker pool with `threads` threads. The optimiser's one-at-a-time
    //! simulations and the before/after ones run on the calling thread either way.
    std::shared_ptr<TrackBatches> batches;
};

struct FittedParameter {
    FitParameter parameter;
    double x = 0.0, initial_value = 0.0, value = 0.0;
    double sigma = 0.0;  //!< one standard deviation of value (NaN where not identifiable)
    bool at_bound = false;
};

struct CalibrationResult {
    std::vector<FittedParameter> fitted;
    std::vector<double> x;
    double misfit_before_m = 0.0, misfit_after_m = 0.0, motion_rms_m = 0.0;
    bool good_fit = false;
    int optimiser_simulations = 0, jacobian_simulations = 0;
    int optimiser_passes = 0;  //!< BOBYQA runs (restarts included)
    int scan_simulations = 0;  //!< of optimiser_simulations, the parallel scan of the box
    //! The Gauss-Newton polish after BOBYQA (evo/calibrate/gauss_newton_polish.hpp): steps taken
    //! (each lowered the misfit), its simulations (of optimiser_simulations: line-search trials
    //! and the Jacobians at the points reached), why it stopped, and the misfit before it.
    int polish_steps = 0, polish_simulations = 0;
    std::string polish_stop;
    double misfit_before_polish_m = 0.0;
    std::string stop_reason;
    //! False when the best point was not reached by an optimiser pass that stopped by its own
    //! criterion (the pass hit the simulation budget, or the budget left no pass to run from the
    //! scan's best): the values are the best found, not an optimum, and the standard deviations
    //! (the curvature at that point) understate how far off they may be.
    bool converged = true;
    Identifiability identifiability;
    SimulatedTrack before, after;
    FitPoint calibrated;  //!< the experiment with the fitted values (and the phase lag)
    double wall_s = 0.0;
    //! One line per finding a reader must not miss (trade-offs, no effect, at a bound, poor fit).
    std::vector<std::string> warnings;
};

CalibrationResult calibrate(const Experiment& experiment, const Body& framed_body,
                            const MeasuredTrack& track, const std::vector<FitParameter>& parameters,
                            const CalibrationOptions& options);

}  // namespace bhm::evo
