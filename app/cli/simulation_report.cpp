#include "app/cli/simulation_report.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <limits>

namespace bhm::app {

namespace {

double norm(double a, double b, double c = 0.0) {
    return std::sqrt(a * a + b * b + c * c);
}

nlohmann::ordered_json vec_json(const Vec3& v) {
    return nlohmann::ordered_json::array({v[0], v[1], v[2]});
}

// Sample times are sums of time steps, so a sample meant for t = settle_s may land a rounding
// error short of it; a nanosecond is far below any time step the engine takes.
constexpr double kTimeSlack_s = 1e-9;

}  // namespace

std::vector<int> tip_layer_voxels(const engine::Model& model) {
    int highest_x = std::numeric_limits<int>::min();
    for (int v = 0; v < model.voxel_count(); ++v)
        highest_x = std::max(highest_x, model.voxel_coords(v)[0]);
    std::vector<int> tip;
    for (int v = 0; v < model.voxel_count(); ++v)
        if (model.voxel_coords(v)[0] == highest_x) tip.push_back(v);
    return tip;
}

Vec3 centroid_m(const engine::World& world, const std::vector<int>& voxels) {
    if (voxels.empty()) {
        const double nan = std::numeric_limits<double>::quiet_NaN();
        return {nan, nan, nan};
    }
    Vec3 sum{0.0, 0.0, 0.0};
    for (int v : voxels) {
        const auto p = world.voxel_position_m(v);
        for (int i = 0; i < 3; ++i)
            sum[i] += p[i];
    }
    const double n = static_cast<double>(voxels.size());
    return {sum[0] / n, sum[1] / n, sum[2] / n};
}

TrajectorySample measure_sample(const engine::World& world, const std::vector<int>& tip_voxels) {
    return {world.time_s(), world.centre_of_mass_m(), centroid_m(world, tip_voxels)};
}

DisplacementSummary summarize_displacements(const std::vector<TrajectorySample>& samples,
                                            double settle_s, double voxel_size_m) {
    DisplacementSummary s;
    if (samples.empty()) return s;
    const auto start = std::find_if(samples.begin(), samples.end(), [&](const TrajectorySample& x) {
        return x.t_s >= settle_s - kTimeSlack_s;
    });
    s.com_end_m = samples.back().com_m;
    s.tip_position_m = samples.back().tip_m;
    if (start == samples.end()) {
        // The run stopped before settling ended: nothing was evaluated, so nothing moved.
        s.com_start_m = s.com_end_m;
        s.com_start_t_s = samples.back().t_s;
        return s;
    }
    s.settled = true;
    s.com_start_t_s = start->t_s;
    s.com_start_m = start->com_m;
    const auto& c0 = s.com_start_m;
    const auto in_voxels_3d = [&](const Vec3& c) {
        return norm(c[0] - c0[0], c[1] - c0[1], c[2] - c0[2]) / voxel_size_m;
    };
    const auto in_voxels_yz = [&](const Vec3& c) {
        return norm(c[1] - c0[1], c[2] - c0[2]) / voxel_size_m;
    };
    s.displacement_3d_voxels = in_voxels_3d(s.com_end_m);
    s.displacement_yz_voxels = in_voxels_yz(s.com_end_m);
    for (auto it = start; it != samples.end(); ++it) {
        s.max_displacement_3d_voxels =
            std::max(s.max_displacement_3d_voxels, in_voxels_3d(it->com_m));
        s.max_displacement_yz_voxels =
            std::max(s.max_displacement_yz_voxels, in_voxels_yz(it->com_m));
    }
    return s;
}

std::string trajectory_csv(const std::vector<TrajectorySample>& samples) {
    std::string out = "t_s,com_x_m,com_y_m,com_z_m,tip_x_m,tip_y_m,tip_z_m\n";
    out.reserve(out.size() + samples.size() * 7 * 24);
    char buffer[40];
    for (const auto& s : samples) {
        const double values[7] = {s.t_s,      s.com_m[0], s.com_m[1], s.com_m[2],
                                  s.tip_m[0], s.tip_m[1], s.tip_m[2]};
        for (int i = 0; i < 7; ++i) {
            // %.17g round-trips any double.
            std::snprintf(buffer, sizeof buffer, "%.17g", values[i]);
            out += buffer;
            out += i + 1 < 7 ? ',' : '\n';
        }
    }
    return out;
}

engine::Replay replay_header(const engine::Model& model, double settle_s) {
    const engine::BodySpec& spec = model.spec();
    engine::Replay r;
    r.nx = spec.nx;
    r.ny = spec.ny;
    r.nz = spec.nz;
    r.voxel_size_m = model.voxel_size_m();
    r.settle_s = settle_s;
    const int n = model.voxel_count();
    r.voxel_cell.resize(n);
    r.voxel_material.resize(n);
    r.voxel_fixed.resize(n);
    for (int v = 0; v < n; ++v) {
        r.voxel_cell[v] = model.voxel_cell(v);
        r.voxel_material[v] = static_cast<std::uint8_t>(model.voxel_material(v));
        r.voxel_fixed[v] = model.voxel_fixed(v) ? 1 : 0;
    }
    return r;
}

SimulationRecorder::SimulationRecorder(const engine::Model& model, double settle_s,
                                       bool record_replay)
    : tip_voxels_(tip_layer_voxels(model)),
      settle_s_(settle_s),
      record_replay_(record_replay),
      replay_(replay_header(model, settle_s)) {}

void SimulationRecorder::observe(const engine::World& world) {
    if (world.steps() == last_step_) return;
    last_step_ = world.steps();
    samples_.push_back(measure_sample(world, tip_voxels_));
    if (record_replay_) {
        replay_.frames.emplace_back();
        world.read_poses(replay_.frames.back());
        replay_.frames.back().time_s = world.time_s();
    }
}

nlohmann::ordered_json summary_json(const RunStats& stats, const DisplacementSummary& d) {
    nlohmann::ordered_json j;
    j["voxels"] = stats.voxels;
    j["links"] = stats.links;
    j["steps"] = stats.steps;
    j["dt_s"] = stats.dt_s;
    j["sim_time_s"] = stats.sim_time_s;
    j["wall_s"] = stats.wall_s;
    j["voxel_steps_per_s"] = stats.voxel_steps_per_s();
    j["diverged"] = stats.diverged;
    j["divergence_reason"] = stats.divergence_reason;
    j["settled"] = d.settled;
    j["com_start_t_s"] = d.com_start_t_s;
    j["com_start_m"] = vec_json(d.com_start_m);
    j["com_end_m"] = vec_json(d.com_end_m);
    j["displacement_3d_voxels"] = d.displacement_3d_voxels;
    j["displacement_yz_voxels"] = d.displacement_yz_voxels;
    j["max_displacement_3d_voxels"] = d.max_displacement_3d_voxels;
    j["max_displacement_yz_voxels"] = d.max_displacement_yz_voxels;
    j["tip_position_m"] = vec_json(d.tip_position_m);
    return j;
}

RunStats run_stats_of(const engine::Model& model, const engine::World& world, double wall_s) {
    RunStats stats;
    stats.voxels = model.voxel_count();
    stats.links = model.link_count();
    stats.steps = world.steps();
    stats.dt_s = model.dt_s();
    stats.sim_time_s = world.time_s();
    stats.wall_s = wall_s;
    stats.diverged = world.diverged();
    stats.divergence_reason = world.divergence_reason();
    return stats;
}

}  // namespace bhm::app
