#include "app/cli/simulation_limits.hpp"

#include <cmath>

#include "engine/io/text_file.hpp"
#include "engine/limits.hpp"
#include "evo/calibrate/track_simulation.hpp"

namespace bhm::app {

std::string simulation_budget_problem(const engine::Model& model,
                                      const evo::Experiment& experiment, double total_s) {
    if (!std::isfinite(total_s) || !(total_s > 0.0))
        return "the simulated time must be a positive finite number of seconds, got " +
               engine::format_number(total_s);
    // The experiment passed the envelope for its own duration; other durations and this body's
    // actual step are checked by the same rule.
    const std::string budget = engine::limits::step_budget_problem(
        {model.dt_s(), model.dt_s()}, total_s, experiment.actuation.frequency_hz,
        experiment.actuation.temperature_amplitude_c > 0, model.voxel_count());
    if (!budget.empty())
        return "cannot simulate " + engine::format_number(total_s) + " s: " + budget;
    return "";
}

std::string simulation_seconds_problem(const engine::Model& model,
                                       const evo::Experiment& experiment, double total_s) {
    if (auto budget = simulation_budget_problem(model, experiment, total_s); !budget.empty())
        return budget;
    // A sampling period longer than the whole simulation records only its two ends, and the
    // summary then reports a maximum displacement of 0 as if the body had not moved (issue 26).
    const double fps = experiment.simulation.record_fps;
    if (fps * total_s < 1.0)
        return "simulation.record_fps " + engine::format_number(fps) +
               " records no sample between the start and the end of the " +
               engine::format_number(total_s) + " s simulation; raise it to at least " +
               engine::format_number(1.0 / total_s);
    return "";
}

std::string track_budget_problem(const engine::Model& model, const evo::Experiment& experiment,
                                 const evo::MeasuredTrack& track) {
    // parse_measured_track refuses a track of fewer than 3 rows; this one was never read.
    if (track.t_s.empty()) return track.source + ": t_s: the track has no rows";
    const std::string why = simulation_budget_problem(model, experiment, track.t_s.back());
    if (why.empty()) return "";
    return track.source + ": " + evo::track_end_field(track) + ": " + why;
}

}  // namespace bhm::app
