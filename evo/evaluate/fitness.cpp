#include "evo/evaluate/fitness.hpp"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <numbers>
#include <thread>

#include "engine/limits.hpp"
#include "engine/world.hpp"
#include "evo/evaluate/behaviour.hpp"
#include "evo/experiment/scene.hpp"

namespace bhm::evo {

namespace {

using Vec3 = std::array<double, 3>;

double norm(const Vec3& v) {
    return std::sqrt(v[0] * v[0] + v[1] * v[1] + v[2] * v[2]);
}

std::size_t measure_index(FitnessMeasure m) {
    return static_cast<std::size_t>(m);
}

//! The face whose layer is the base of the bend: the first fixed face, x- if none is fixed.
Face bend_base_face(const Boundary& boundary) {
    for (int f = 0; f < 6; ++f)
        if (boundary.faces[static_cast<std::size_t>(f)] == BoundaryKind::Fixed)
            return static_cast<Face>(f);
    return Face::XMin;
}

}  // namespace

double fitness_under(const FitnessReport& report, FitnessMeasure measure) {
    return report.diverged ? kDivergedFitness : report.measures[measure_index(measure)];
}

double fitness_under(const FitnessReport& report, const Fitness& rules) {
    if (rejected_by_exploit(report.exploits, rules.constraints)) return kInvalidFitness;
    return fitness_under(report, rules.measure);
}

BendLayers bend_layers(const Experiment& experiment, const engine::World& world) {
    BendLayers layers;
    const auto& model = world.model();
    const Face face = bend_base_face(experiment.boundary);
    const auto axis = static_cast<std::size_t>(face) / 2;
    const bool base_on_high_side = static_cast<int>(face) % 2 == 1;
    const int n = model.voxel_count();
    if (n == 0) return layers;
    int lo = model.voxel_coords(0)[axis], hi = lo;
    for (int v = 1; v < n; ++v) {
        lo = std::min(lo, model.voxel_coords(v)[axis]);
        hi = std::max(hi, model.voxel_coords(v)[axis]);
    }
    if (lo == hi) return layers;  // one layer: no line to bend
    const int base_layer = base_on_high_side ? hi : lo;
    const int tip_layer = base_on_high_side ? lo : hi;
    for (int v = 0; v < n; ++v) {
        const int c = model.voxel_coords(v)[axis];
        if (c == base_layer) layers.base.push_back(v);
        if (c == tip_layer) layers.tip.push_back(v);
    }
    return layers;
}

MeasureTracker::MeasureTracker(const Experiment& experiment, const engine::World& world)
    : settle_s_(experiment.simulation.settle_s), voxel_size_m_(experiment.voxel_size_m) {
    auto layers = bend_layers(experiment, world);
    base_voxels_ = std::move(layers.base);
    tip_voxels_ = std::move(layers.tip);
}

std::array<double, 3> MeasureTracker::centroid(const engine::World& world,
                                               const std::vector<int>& voxels) const {
    Vec3 sum{0.0, 0.0, 0.0};
    for (int v : voxels) {
        const auto p = world.voxel_position_m(v);
        for (int k = 0; k < 3; ++k)
            sum[static_cast<std::size_t>(k)] += p[static_cast<std::size_t>(k)];
    }
    for (auto& s : sum)
        s /= static_cast<double>(voxels.size());
    return sum;
}

void MeasureTracker::observe(const engine::World& world) {
    // Samples land on or just after their nominal time; the tolerance keeps t = settle_s itself.
    if (world.time_s() < settle_s_ - 1e-9) return;
    const Vec3 com = world.center_of_mass_m();
    const bool can_bend = !base_voxels_.empty() && !tip_voxels_.empty();
    Vec3 direction{0.0, 0.0, 0.0};
    if (can_bend) {
        const Vec3 base = centroid(world, base_voxels_), tip = centroid(world, tip_voxels_);
        for (std::size_t k = 0; k < 3; ++k)
            direction[k] = tip[k] - base[k];
    }
    if (!has_reference_) {
        has_reference_ = true;
        com0_ = com;
        direction0_ = direction;
        return;  // every measure is 0 at the reference
    }
    const Vec3 d{com[0] - com0_[0], com[1] - com0_[1], com[2] - com0_[2]};
    const double d3 = norm(d) / voxel_size_m_;
    const double dyz = std::sqrt(d[1] * d[1] + d[2] * d[2]) / voxel_size_m_;
    auto& m = measures_;
    m[measure_index(FitnessMeasure::ComFinal3d)] = d3;
    m[measure_index(FitnessMeasure::ComFinalYz)] = dyz;
    m[measure_index(FitnessMeasure::ComMax3d)] =
        std::max(m[measure_index(FitnessMeasure::ComMax3d)], d3);
    m[measure_index(FitnessMeasure::ComMaxYz)] =
        std::max(m[measure_index(FitnessMeasure::ComMaxYz)], dyz);
    if (can_bend) {
        const double lengths = norm(direction0_) * norm(direction);
        if (lengths > 0.0) {
            const double cosine = (direction0_[0] * direction[0] + direction0_[1] * direction[1] +
                                   direction0_[2] * direction[2]) /
                                  lengths;
            const double angle =
                std::acos(std::clamp(cosine, -1.0, 1.0)) * 180.0 / std::numbers::pi;
            auto& bend = m[measure_index(FitnessMeasure::BendAngleDeg)];
            bend = std::max(bend, angle);
        }
    }
}

namespace {

//! Holds while paused, throws once cancelled.
void honour(const EvaluationControl& control) {
    auto cancelled = [&] {
        return control.cancel && control.cancel->load(std::memory_order_relaxed);
    };
    while (!cancelled() && control.pause && control.pause->load(std::memory_order_relaxed))
        std::this_thread::sleep_for(std::chrono::milliseconds(20));
    if (cancelled()) throw EvaluationCancelled();
}

//! engine::run's schedule (observe at t = 0, every 1 / sample_hz and at total_s; stop on
//! divergence), advanced in slices of kControlCheckSteps steps so the controls are seen often.
//! Slicing changes nothing: dt is fixed and advance_to stops at the first step at or past its
//! target, so the same steps are taken (tests/evo/test_fitness.cpp checks against engine::run).
void run_controlled(engine::World& world, double total_s, double sample_hz,
                    const EvaluationControl& control, MeasureTracker& tracker,
                    ExploitTracker& exploits, BehaviourTracker& behaviour) {
    const double period = 1.0 / sample_hz;
    const double dt = world.model().dt_s();
    const double half_step = 0.5 * dt;
    if (world.diverged()) return;
    // As engine::run: never silently zero steps (limits::step_budget_problem refuses it up front).
    if (world.steps() == 0 && total_s > 0.0 && engine::limits::steps_for(total_s, dt) == 0)
        throw std::invalid_argument("evaluation: a step of " + std::to_string(dt) +
                                    " s is longer than twice the " + std::to_string(total_s) +
                                    " s to simulate: zero steps would run");
    honour(control);
    tracker.observe(world);
    exploits.observe(world);
    behaviour.observe(world);
    if (world.time_s() >= total_s - half_step) return;
    for (std::int64_t k = 1;; ++k) {
        double due = static_cast<double>(k) * period;
        const bool last = due >= total_s - half_step;
        if (last) due = total_s;
        while (world.time_s() < due) {
            const double slice_end = static_cast<double>(world.steps() + kControlCheckSteps) * dt;
            if (!world.advance_to(std::min(due, slice_end))) return;  // diverged
            honour(control);
        }
        tracker.observe(world);
        exploits.observe(world);
        behaviour.observe(world);
        if (last) return;
    }
}

}  // namespace

FitnessReport evaluate_body(const Experiment& experiment, const Body& framed_body,
                            const std::atomic<bool>* cancel) {
    return evaluate_body(experiment, framed_body, EvaluationControl{cancel, nullptr});
}

FitnessReport evaluate_body(const Experiment& experiment, const Body& framed_body,
                            const EvaluationControl& control) {
    const auto start = std::chrono::steady_clock::now();
    // Random phases come from the run's seed (docs/experiment-format.md), which the experiment
    // holds.
    const auto spec = make_body_spec(experiment, framed_body, experiment.evolution.seed);
    engine::World world(engine::Model::build(spec));
    MeasureTracker tracker(experiment, world);
    ExploitTracker exploits(experiment, world);
    BehaviourTracker behaviour(experiment, world);
    const double sample_hz =
        experiment.simulation.record_fps > 0.0 ? experiment.simulation.record_fps : 30.0;
    run_controlled(world, evaluation_seconds(experiment), sample_hz, control, tracker, exploits,
                   behaviour);

    FitnessReport report;
    report.measures = tracker.measures();
    report.simulated_s = world.time_s();
    report.steps = world.steps();
    report.diverged = world.diverged();
    if (report.diverged) report.divergence_reason = world.divergence_reason();
    const bool finite = std::all_of(report.measures.begin(), report.measures.end(),
                                    [](double v) { return std::isfinite(v); });
    if (!report.diverged && !finite) {
        report.diverged = true;
        report.divergence_reason = "non-finite fitness measure";
    }
    if (report.diverged)
        report.measures.fill(0.0);  // keep files free of NaN; fitness says diverged
    report.exploits = exploits.report(report.diverged);
    if (!report.diverged) report.behaviour = behaviour.descriptor();
    report.fitness = fitness_under(report, experiment.fitness);
    report.sim_wall_s =
        std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
    return report;
}

}  // namespace bhm::evo
