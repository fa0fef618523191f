#include "evo/evaluate/simulate.hpp"

#include <algorithm>
#include <chrono>
#include <cmath>

#include "evo/evaluate/behaviour.hpp"
#include "evo/evaluate/exploit_flags.hpp"
#include "evo/evaluate/periodic_end.hpp"
#include "evo/evaluate/settle_rest.hpp"
#include "evo/experiment/body_spec_of.hpp"

namespace bhm::evo {

std::shared_ptr<const engine::Model> model_of(const Experiment& experiment, const Body& framed_body,
                                              std::optional<std::uint64_t> phase_seed) {
    // Random phases come from the run's seed (docs/experiment-format.md), which the experiment
    // holds.
    return engine::Model::build(
        make_body_spec(experiment, framed_body, phase_seed.value_or(experiment.evolution.seed)));
}

SimulationResult simulate(const Experiment& experiment_in,
                          std::shared_ptr<const engine::Model> model,
                          const SimulationOptions& options, const SimulationHooks& hooks) {
    const auto start = std::chrono::steady_clock::now();
    // The measures count from settle_s to the end of what is simulated.
    Experiment experiment = experiment_in;
    const double settle_s = experiment.simulation.settle_s;
    if (options.seconds && *options.seconds > settle_s)
        experiment.simulation.evaluate_s = *options.seconds - settle_s;
    const double total_s = options.seconds.value_or(evaluation_seconds(experiment_in));
    if (!options.end_early) experiment.simulation.end_when_periodic = false;

    SimulationResult sim{model, engine::World(model), {}};
    engine::World& world = sim.world;
    TrackSampler sampler(experiment, world);
    MeasureTracker tracker(experiment, world);
    ExploitTracker exploits(experiment, world);
    BehaviourTracker behaviour(experiment, world);
    const bool held = every_part_held(*model);
    PeriodicEnd periodic(experiment, model->dt_s(), sampler.groups(), held);
    SettleRest rest(experiment, sampler.groups(), held);
    auto observe = [&](const TrackSample& sample) {
        tracker.observe(sample);
        exploits.observe(sample);
        behaviour.observe(sample);
        if (hooks.sampled) hooks.sampled(sample);
    };
    const double sample_hz =
        experiment.simulation.record_fps > 0.0 ? experiment.simulation.record_fps : 30.0;
    bool repeats = false, resting = false;
    TrackSample last;
    auto take = [&](const TrackSample& sample) {
        observe(sample);
        repeats = periodic.observe(sample);
        resting = rest.observe(sample);
        last = sample;
    };
    // Each sample at its due time (evo/evaluate/tracks.hpp): the tracks one step before it are
    // kept, and the sample interpolated between them and the step at or past it. A run's first
    // sample (t = 0, or where simulation resumes after resting) has no step before it: it is due
    // at `due`, set before each engine::run.
    double due = 0.0;
    engine::RunHooks run_hooks;
    run_hooks.before_sample = [&](const engine::World& w, double due_s) {
        sampler.before(w, due_s);
        due = due_s;
    };
    run_hooks.observe = [&](const engine::World& w) {
        if (hooks.record) hooks.record(w);
        take(sampler.sample_at(w, due));
    };
    run_hooks.poll = [&](const engine::World& w) {
        if (hooks.poll) hooks.poll(w);
        return repeats || resting ? engine::RunVerdict::Stop : engine::RunVerdict::Continue;
    };
    run_hooks.poll_steps = kControlCheckSteps;
    engine::run(world, total_s, sample_hz, run_hooks);
    if (resting && !world.diverged()) {
        // At rest before settle_s (evo/evaluate/settle_rest.hpp): the rest of the settling passes
        // without integrating, its samples are the last one's; simulation resumes at the first
        // sample at or past settle_s, exactly where the full run takes it.
        const double dt = model->dt_s();
        for (std::int64_t k = rest.next_sample(); k < rest.settled_sample(); ++k) {
            TrackSample still = last;
            still.t_s = sample_due_s(k, 1.0 / sample_hz, total_s, dt);
            take(still);
        }
        resting = false;
        // At rest the step before the due time is the state itself: the sample is the world's.
        due = sample_due_s(rest.settled_sample(), 1.0 / sample_hz, total_s, dt);
        world.rest_until(due);
        engine::run(world, total_s, sample_hz, run_hooks);
    }
    const bool ended_early = repeats && !world.diverged();
    if (ended_early) periodic.extrapolate(observe);

    FitnessReport& report = sim.report;
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
    return sim;
}

}  // namespace bhm::evo
