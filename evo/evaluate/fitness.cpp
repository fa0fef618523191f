#include "evo/evaluate/fitness.hpp"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <numbers>
#include <thread>

#include "engine/world.hpp"
#include "evo/evaluate/behaviour.hpp"
#include "evo/evaluate/simulate.hpp"

namespace bhm::evo {

namespace {

double norm(const Vec3& v) {
    return std::sqrt(v[0] * v[0] + v[1] * v[1] + v[2] * v[2]);
}

std::size_t measure_index(FitnessMeasure m) {
    return static_cast<std::size_t>(m);
}

}  // namespace

double fitness_under(const FitnessReport& report, FitnessMeasure measure) {
    return report.diverged ? kDivergedFitness : report.measures[measure_index(measure)];
}

double fitness_under(const FitnessReport& report, const Fitness& rules) {
    if (rejected_by_exploit(report.exploits, rules.constraints)) return kInvalidFitness;
    return fitness_under(report, rules.measure);
}

MeasureTracker::MeasureTracker(const Experiment& experiment, const engine::World& world)
    : settle_s_(experiment.simulation.settle_s),
      voxel_size_m_(experiment.voxel_size_m),
      own_sampler_(std::make_unique<TrackSampler>(experiment, world)) {
    can_bend_ = !own_sampler_->layers().base.empty() && !own_sampler_->layers().tip.empty();
}

void MeasureTracker::observe(const engine::World& world) {
    observe(own_sampler_->sample(world));
}

void MeasureTracker::observe(const TrackSample& sample) {
    if (!settled(sample.t_s, settle_s_)) return;
    const Vec3& com = sample.com_m;
    const bool can_bend = can_bend_;
    Vec3 direction{0.0, 0.0, 0.0};
    if (can_bend) {
        const Vec3& base = sample.bend_base_m;
        const Vec3& tip = sample.bend_tip_m;
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

}  // namespace

FitnessReport evaluate_body(const Experiment& experiment, const Body& framed_body,
                            const std::atomic<bool>* cancel) {
    return evaluate_body(experiment, framed_body, EvaluationControl{cancel, nullptr});
}

FitnessReport evaluate_body(const Experiment& experiment, const Body& framed_body,
                            const EvaluationControl& control) {
    SimulationHooks hooks;
    hooks.poll = [&](const engine::World&) { honour(control); };
    return simulate(experiment, model_of(experiment, framed_body), {}, hooks).report;
}

}  // namespace bhm::evo
