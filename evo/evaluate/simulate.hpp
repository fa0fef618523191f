#pragma once
// One simulation of one body under an experiment: the recipe every caller shares (issue 22) -
// the evaluation (evaluate_body), the studio's replay of a body, `bhm simulate` and the Python
// module. The spec with the run's actuation phases, the model, engine::run's sampling at
// record_fps, the trackers every measure comes from (evo/evaluate/tracks.hpp), and, for an
// evaluation, the two early ends (settling at rest, evo/evaluate/settle_rest.hpp; motion that
// repeats, evo/evaluate/periodic_end.hpp). A caller adds what only it needs through hooks (a
// recorder, a progress line, a cancel) and reads one FitnessReport back, so the numbers a replay
// shows are the ones evolution measured.
#include <cstdint>
#include <functional>
#include <memory>
#include <optional>

#include "engine/model.hpp"
#include "engine/world.hpp"
#include "evo/evaluate/fitness.hpp"
#include "evo/evaluate/tracks.hpp"
#include "evo/experiment/experiment.hpp"

namespace bhm::evo {

//! The model of a framed body (apply_frame_and_overrides output) with random actuation phases
//! drawn from phase_seed (experiment.evolution.seed when empty, as an evaluation draws them).
//! Throws std::invalid_argument with a one-line reason for a body that cannot be simulated.
std::shared_ptr<const engine::Model> model_of(const Experiment& experiment, const Body& framed_body,
                                              std::optional<std::uint64_t> phase_seed = {});

struct SimulationOptions {
    //! Seconds to simulate from t = 0; empty: evaluation_seconds(experiment). Measures count
    //! from settle_s to the end either way.
    std::optional<double> seconds;
    //! An evaluation ends early where the experiment allows (end_when_periodic); a replay or
    //! `bhm simulate` runs the whole time.
    bool end_early = true;
};

struct SimulationHooks {
    //! Every simulated sample (t = 0, every 1 / record_fps, the end), before the trackers.
    std::function<void(const engine::World&)> record;
    //! Every sample the measures see, simulated or not (settling passed at rest, an
    //! extrapolated end), in order.
    std::function<void(const TrackSample&)> sampled;
    //! Every kControlCheckSteps steps and after each sample: pause (by waiting) or cancel (by
    //! throwing). Never changes the steps taken.
    std::function<void(const engine::World&)> poll;
};

struct SimulationResult {
    std::shared_ptr<const engine::Model> model;
    engine::World world;  //!< where the simulation stopped
    FitnessReport report;
};

//! Runs the recipe on a model built by model_of. report.sim_wall_s is the time run here.
SimulationResult simulate(const Experiment& experiment, std::shared_ptr<const engine::Model> model,
                          const SimulationOptions& options = {}, const SimulationHooks& hooks = {});

}  // namespace bhm::evo
