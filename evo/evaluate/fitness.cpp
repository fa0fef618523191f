#include "evo/evaluate/fitness.hpp"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <numbers>
#include <thread>

#include "engine/world.hpp"
#include "evo/evaluate/behaviour.hpp"
#include "evo/evaluate/periodic_end.hpp"
#include "evo/evaluate/settle_rest.hpp"
#include "evo/experiment/body_spec_of.hpp"

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
    const auto start = std::chrono::steady_clock::now();
    // Random phases come from the run's seed (docs/experiment-format.md), which the experiment
    // holds.
    const auto spec = make_body_spec(experiment, framed_body, experiment.evolution.seed);
    engine::World world(engine::Model::build(spec));
    TrackSampler sampler(experiment, world);
    MeasureTracker tracker(experiment, world);
    ExploitTracker exploits(experiment, world);
    BehaviourTracker behaviour(experiment, world);
    const bool held = every_part_held(world.model());
    PeriodicEnd periodic(experiment, world.model().dt_s(), sampler.groups(), held);
    SettleRest rest(experiment, sampler.groups(), held);
    auto observe = [&](const TrackSample& sample) {
        tracker.observe(sample);
        exploits.observe(sample);
        behaviour.observe(sample);
    };
    const double sample_hz =
        experiment.simulation.record_fps > 0.0 ? experiment.simulation.record_fps : 30.0;
    const double total_s = evaluation_seconds(experiment);
    bool repeats = false, resting = false;
    TrackSample last;
    auto take = [&](const TrackSample& sample) {
        observe(sample);
        repeats = periodic.observe(sample);
        resting = rest.observe(sample);
        last = sample;
    };
    engine::RunHooks hooks;
    hooks.observe = [&](const engine::World& w) { take(sampler.sample(w)); };
    hooks.poll = [&](const engine::World&) {
        honour(control);
        return repeats || resting ? engine::RunVerdict::Stop : engine::RunVerdict::Continue;
    };
    hooks.poll_steps = kControlCheckSteps;
    engine::run(world, total_s, sample_hz, hooks);
    if (resting && !world.diverged()) {
        // At rest before settle_s (evo/evaluate/settle_rest.hpp): the rest of the settling passes
        // without integrating, its samples are the last one's; simulation resumes at the first
        // sample at or past settle_s, exactly where the full run takes it.
        const double dt = world.model().dt_s();
        for (std::int64_t k = rest.next_sample(); k < rest.settled_sample(); ++k) {
            TrackSample still = last;
            still.t_s = sample_time_s(k, 1.0 / sample_hz, total_s, dt);
            take(still);
        }
        resting = false;
        world.rest_until(sample_time_s(rest.settled_sample(), 1.0 / sample_hz, total_s, dt));
        engine::run(world, total_s, sample_hz, hooks);
    }
    const bool ended_early = repeats && !world.diverged();
    if (ended_early) periodic.extrapolate(observe);

    FitnessReport report;
    report.measures = tracker.measures();
    report.simulated_s = world.time_s();
    report.steps = world.integrated_steps();
    report.ended_early = ended_early;
    report.periodic_residual = periodic.residual_voxels();
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
