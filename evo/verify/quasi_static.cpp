#include "evo/verify/quasi_static.hpp"

#include <algorithm>
#include <cmath>
#include <ctime>
#include <map>
#include <numbers>
#include <stdexcept>

#include "engine/model.hpp"
#include "engine/world.hpp"
#include "evo/verify/ccx_deck.hpp"
#include "evo/verify/verify_progress.hpp"

namespace bhm::evo {

QuasiStaticResult engine_quasi_static(const engine::BodySpec& body, double temperature_c,
                                      const QuasiStaticOptions& options) {
    const std::clock_t cpu_start = std::clock();
    engine::BodySpec spec = body;
    spec.environment.floor = false;
    spec.damping.global_ratio = std::max(spec.damping.global_ratio, options.global_damping_ratio);
    spec.actuation.frequency_hz = 0.0;
    spec.actuation.start_s = 0.0;
    spec.actuation.temperature_amplitude_c = std::fabs(temperature_c);
    spec.phase_rad.assign(spec.material.size(), static_cast<float>(
                                                    (temperature_c < 0.0 ? -0.5 : 0.5) *
                                                    std::numbers::pi));
    if (muscle_driven(body)) {
        if (temperature_c != 0.0 && temperature_c != 1.0)
            throw std::invalid_argument(
                "a muscle body's static load is its activation, 0 or "
                "1, not " +
                std::to_string(temperature_c));
        // Stimulated throughout (one pulse as wide as its period), one signal for every muscle.
        for (engine::Material& m : spec.materials) {
            if (m.actuation_model != engine::ActuationModel::Muscle) continue;
            m.muscle.stimulus = engine::MuscleStimulus::PulseTrain;
            m.muscle.frequency_hz = 1.0;
            m.muscle.pulse_width_s = 1.0;
            m.muscle.train_on_s = m.muscle.train_off_s = 0.0;
            m.muscle.rise_s = m.muscle.decay_s = kHoldRiseS;
            m.muscle.fatigue_s = 0.0;  // peak activation is the fresh muscle's
        }
        spec.actuation.start_s = temperature_c == 1.0 ? 0.0 : options.max_time_s + 1.0;
        // A static load has no timing: every muscle voxel stimulated at once (a phase would
        // delay its stimulus, engine/muscle.hpp).
        spec.phase_rad.assign(spec.material.size(), 0.0f);
    }
    auto model = engine::Model::build(spec);
    engine::World world(model);
    const int n = model->voxel_count();
    // Voxels by lattice cell, so that the answer is in the FemModel's order.
    std::map<int, int> by_cell;
    for (int v = 0; v < n; ++v)
        by_cell[model->voxel_cell(v)] = v;
    std::vector<std::array<double, 3>> start(static_cast<std::size_t>(n)), last;
    for (int v = 0; v < n; ++v)
        start[static_cast<std::size_t>(v)] = world.voxel_position_m(v);
    last = start;

    QuasiStaticResult result;
    const double slice_s = 0.05;
    for (int slice = 1; slice * slice_s <= options.max_time_s + 1e-9; ++slice) {
        if (options.cancel && options.cancel->load(std::memory_order_relaxed))
            throw VerifyCancelled();
        if (!world.advance_to(slice * slice_s)) {
            result.problem = "the engine diverged at t = " + std::to_string(world.time_s()) +
                             " s (" + world.divergence_reason() + ")";
            break;
        }
        double moved2 = 0.0, displaced2 = 0.0;
        for (int v = 0; v < n; ++v) {
            const auto p = world.voxel_position_m(v);
            for (int a = 0; a < 3; ++a) {
                const double d = p[a] - last[static_cast<std::size_t>(v)][a];
                const double u = p[a] - start[static_cast<std::size_t>(v)][a];
                moved2 += d * d;
                displaced2 += u * u;
            }
            last[static_cast<std::size_t>(v)] = p;
        }
        const double floor = 1e-6 * spec.voxel_size_m;  // a body that hardly moves is at rest
        if (slice > 2 && std::sqrt(moved2) <= options.tolerance * std::sqrt(displaced2) +
                                                 floor * std::sqrt(static_cast<double>(n))) {
            result.settled = true;
            break;
        }
    }
    result.simulated_s = world.time_s();
    if (!result.settled && result.problem.empty())
        result.problem = "the engine did not come to rest within " +
                         std::to_string(options.max_time_s) + " s";
    engine::VoxelPoses poses;
    world.read_poses(poses);
    auto& shape = result.shape;
    shape.time_s = poses.time_s;
    for (const auto& [cell, v] : by_cell) {
        (void)cell;
        std::array<double, 3> u{};
        for (int a = 0; a < 3; ++a)
            u[a] = last[static_cast<std::size_t>(v)][a] - start[static_cast<std::size_t>(v)][a];
        result.displacement_m.push_back(u);
        result.rest_position_m.push_back(start[static_cast<std::size_t>(v)]);
        const auto k = static_cast<std::size_t>(v);
        shape.position_m.insert(shape.position_m.end(), poses.position_m.begin() + 3 * k,
                                poses.position_m.begin() + 3 * k + 3);
        shape.orientation.insert(shape.orientation.end(), poses.orientation.begin() + 4 * k,
                                 poses.orientation.begin() + 4 * k + 4);
        shape.size_m.insert(shape.size_m.end(), poses.size_m.begin() + 3 * k,
                            poses.size_m.begin() + 3 * k + 3);
    }
    result.cpu_s = static_cast<double>(std::clock() - cpu_start) / CLOCKS_PER_SEC;
    return result;
}

}  // namespace bhm::evo
