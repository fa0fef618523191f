#include "evo/calibrate/track_simulation.hpp"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <limits>
#include <memory>
#include <stdexcept>

#include "engine/model.hpp"
#include "engine/world.hpp"
#include "evo/evaluate/fitness.hpp"
#include "evo/evaluate/tracks.hpp"
#include "evo/experiment/body_spec_of.hpp"

namespace bhm::evo {

namespace {

// The voxels whose centroid is each point (empty for the centre of mass).
std::vector<std::vector<int>> point_voxels(const Experiment& experiment,
                                           const engine::World& world,
                                           const MeasuredTrack& track) {
    std::vector<std::vector<int>> out;
    for (const auto& p : track.points) {
        if (p.kind == TrackPointKind::Com) {
            out.emplace_back();
        } else if (p.kind == TrackPointKind::Tip) {
            auto tip = bend_layers(experiment, world).tip;
            if (tip.empty())
                throw std::runtime_error(track.source +
                                         ": point 'tip': the body has a single layer along its "
                                         "bend line, so no tip");
            out.push_back(std::move(tip));
        } else {
            int found = -1;
            for (int v = 0; v < world.model().voxel_count(); ++v)
                if (world.model().voxel_cell(v) == p.cell) found = v;
            if (found < 0)
                throw std::runtime_error(track.source + ": point '" + p.name +
                                         "': that lattice cell holds no voxel in the body");
            out.push_back({found});
        }
    }
    return out;
}

}  // namespace

SimulatedTrack simulate_track(const FitPoint& point, const Body& framed_body,
                              const MeasuredTrack& track, const std::atomic<bool>* cancel) {
    const auto start = std::chrono::steady_clock::now();
    const Experiment& e = point.experiment;
    SimulatedTrack sim;
    std::shared_ptr<const engine::Model> model;
    try {
        // The fitted phase lag is in e.actuation.phase_offset_rad (apply_fit).
        model = engine::Model::build(make_body_spec(e, framed_body, e.evolution.seed));
    } catch (const std::invalid_argument& error) {
        // Parameters outside the engine's envelope (a trial of the fit): as good as diverged.
        sim.diverged = true;
        sim.divergence_reason = error.what();
        sim.position_m.assign(track.points.size(), {});
        return sim;
    }
    engine::World world(model);
    const auto voxels = point_voxels(e, world, track);
    sim.position_m.assign(track.points.size(), {});
    auto positions = [&] {
        std::vector<std::array<double, 3>> p(voxels.size());
        for (std::size_t i = 0; i < voxels.size(); ++i)
            p[i] = voxels[i].empty() ? world.centre_of_mass_m() : centroid_of(world, voxels[i]);
        return p;
    };
    // Each sample is interpolated between the steps on either side of its time: the step's
    // length changes with E and density, and taking the first step past the time would add a
    // jitter of up to one step's motion to the misfit, enough to stall the optimiser.
    const double dt = world.model().dt_s();
    for (double t : track.t_s) {
        if (cancel && cancel->load()) throw EvaluationCancelled();
        if (!world.advance_to(t - dt)) break;
        const double t0 = world.time_s();
        const auto p0 = positions();
        if (!world.advance_to(t)) break;
        const double t1 = world.time_s();
        auto p1 = positions();
        const double w = t1 > t0 ? std::clamp((t - t0) / (t1 - t0), 0.0, 1.0) : 1.0;
        for (std::size_t i = 0; i < voxels.size(); ++i) {
            for (std::size_t a = 0; a < 3; ++a) p1[i][a] = p0[i][a] + w * (p1[i][a] - p0[i][a]);
            sim.position_m[i].push_back(p1[i]);
        }
    }
    sim.diverged = world.diverged();
    sim.divergence_reason = world.divergence_reason();
    sim.wall_s = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
    return sim;
}

const char* track_end_field(const MeasuredTrack& track) {
    if (track.t_s.empty()) return "t_s";
    // The offset set the end where it is more of it than the file's own last time.
    const double file_end_s = track.t_s.back() - track.time_offset_s;
    return std::abs(track.time_offset_s) > std::abs(file_end_s) ? "time_offset_s" : "t_s";
}

std::string track_span_warning(const MeasuredTrack& track, const Experiment& experiment) {
    const double experiment_s = evaluation_seconds(experiment);
    if (track.t_s.empty() || !(experiment_s > 0.0)) return {};
    const double end_s = track.t_s.back();
    const double ratio = end_s / experiment_s;
    if (ratio <= kTrackSpanWarningFactor && ratio >= 1.0 / kTrackSpanWarningFactor) return {};
    const std::string field = track_end_field(track);
    char numbers[160];
    std::snprintf(numbers, sizeof numbers,
                  "the track ends at %.4g s, %.4g times the experiment's settle_s + evaluate_s "
                  "(%.4g s)",
                  end_s, ratio, experiment_s);
    return track.source + ": " + field + ": " + numbers +
           ", and every simulation of the calibration runs to its end: is " + field +
           " in seconds?";
}

std::vector<double> track_residuals(const MeasuredTrack& track, const SimulatedTrack& sim) {
    std::vector<double> r;
    if (sim.diverged || sim.position_m.size() < track.points.size()) return r;
    for (std::size_t i = 0; i < track.points.size(); ++i)
        if (sim.position_m[i].size() < track.t_s.size()) return r;  // stopped early
    r.reserve(track.compared_values());
    const std::size_t rows = track.t_s.size();
    // Per point and axis, the offset between the two (a tracker's origin) is the one that fits
    // best: their mean difference. Taking both from their first row instead put that row's
    // tracking error into every residual of its point and axis, a constant offset that a
    // parameter with a quasi-static mark (E of a body on the floor) bent itself to absorb.
    std::vector<double> offset(3 * track.points.size(), 0.0);
    for (std::size_t i = 0; i < track.points.size(); ++i)
        for (std::size_t a = 0; a < 3; ++a)
            if (track.points[i].axes[a]) {
                double sum = 0.0;
                for (std::size_t k = 0; k < rows; ++k)
                    sum += sim.position_m[i][k][a] - track.points[i].position_m[k][a];
                offset[3 * i + a] = sum / static_cast<double>(rows);
            }
    for (std::size_t i = 0; i < track.points.size(); ++i) {
        const auto& measured = track.points[i].position_m;
        const auto& simulated = sim.position_m[i];
        for (std::size_t k = 0; k < rows; ++k)
            for (std::size_t a = 0; a < 3; ++a)
                if (track.points[i].axes[a])
                    r.push_back(simulated[k][a] - measured[k][a] - offset[3 * i + a]);
    }
    return r;
}

double track_misfit(const MeasuredTrack& track, const SimulatedTrack& sim) {
    const auto r = track_residuals(track, sim);
    if (r.empty()) return std::numeric_limits<double>::infinity();
    double sum = 0.0;
    for (double v : r) sum += v * v;
    return std::sqrt(sum / static_cast<double>(r.size()));
}

double track_motion_rms(const MeasuredTrack& track) {
    double sum = 0.0;
    std::size_t n = 0;
    for (const auto& p : track.points)
        for (std::size_t k = 0; k < track.t_s.size(); ++k)
            for (std::size_t a = 0; a < 3; ++a)
                if (p.axes[a]) {
                    const double d = p.position_m[k][a] - p.position_m[0][a];
                    sum += d * d;
                    ++n;
                }
    return n ? std::sqrt(sum / static_cast<double>(n)) : 0.0;
}

}  // namespace bhm::evo
