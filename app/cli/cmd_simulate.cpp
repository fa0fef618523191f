// bhm simulate: one body under one experiment, headless, to summary.json + trajectory.csv +
// replay.bin. The measuring lives in app/cli/simulation_report.hpp; this file only wires it up.
#include <unistd.h>

#include <chrono>
#include <cstdio>
#include <filesystem>
#include <iostream>
#include <stdexcept>
#include <string>

#include "app/cli/arg_parser.hpp"
#include "app/cli/commands.hpp"
#include "app/cli/problem_report.hpp"
#include "app/cli/simulate_progress.hpp"
#include "app/cli/simulation_limits.hpp"
#include "app/cli/simulation_report.hpp"
#include "engine/io/staged_folder.hpp"
#include "engine/limits.hpp"
#include "engine/model.hpp"
#include "engine/replay.hpp"
#include "engine/world.hpp"
#include "evo/evaluate/exploit_flags.hpp"
#include "evo/evaluate/fitness.hpp"
#include "evo/evaluate/periodic_end.hpp"
#include "evo/evaluate/settle_rest.hpp"
#include "evo/evaluate/simulate.hpp"
#include "evo/evaluate/tracks.hpp"
#include "evo/experiment/body_spec_of.hpp"
#include "evo/experiment/experiment_io.hpp"

namespace bhm::app {

namespace {

constexpr int kExitDiverged = 3;

const char* const kSummary =
    "Simulates BODY under EXPERIMENT for settle_s + evaluate_s seconds (or --seconds) and writes\n"
    "into DIR:\n"
    "  summary.json    voxels, links, steps, dt_s, sim_time_s, wall_s, voxel_steps_per_s,\n"
    "                  diverged, divergence_reason, com_start_m (centre of mass at the end of\n"
    "                  settling), com_end_m, displacement_3d_voxels, displacement_yz_voxels,\n"
    "                  max_displacement_3d_voxels, max_displacement_yz_voxels (over the samples\n"
    "                  after settling), tip_position_m (centroid of the highest-x voxel layer),\n"
    "                  exploits {escaped, unanchored_fraction, held_voxels, detached_motion,\n"
    "                  base_motion_ratio, motion_voxels, tentacle, thin_share, thin_voxels}\n"
    "                  (docs/evolution.md, \"Exploit flags\")\n"
    "  trajectory.csv  t_s,com_x_m,com_y_m,com_z_m,tip_x_m,tip_y_m,tip_z_m at record_fps\n"
    "  replay.bin      every voxel's pose at record_fps (docs/replay-format.md)\n"
    "\n"
    "exit status: 0 ok, 1 invalid or missing input (every problem printed as file:field: "
    "message),\n"
    "2 usage error, 3 the simulation diverged (the files are still written, with diverged: true).";

// What bhm simulate writes into its --out folder, which is replaced whole
// (engine/io/staged_folder.hpp): a kill or a failed write leaves the old run's files whole.
bool simulate_output(const std::string& name) {
    return name == "summary.json" || name == "trajectory.csv" || name == "replay.bin";
}

int simulate(ArgParser& args) {
    const std::string experiment_path = args.positionals().at(0);
    if (!args.has("--body")) throw UsageError("missing --body BODY.json");
    const std::string body_path = args.get("--body");
    const std::string out_dir = args.get("--out", "sim-out");
    const auto phase_seed = static_cast<std::uint64_t>(args.get_int("--phase-seed", 0));
    if (args.get_int("--phase-seed", 0) < 0) throw UsageError("--phase-seed must be >= 0");

    if (args.has("--seconds") && !(args.get_double("--seconds", 0.0) > 0.0))
        throw UsageError("--seconds must be positive");

    // Both files are read before reporting, so one run lists every problem of both.
    evo::Experiment experiment;
    evo::Body body;
    try {
        auto loaded = evo::load_experiment_and_body(experiment_path, body_path);
        say_library_warnings(loaded.experiment);
        experiment = std::move(loaded.experiment);
        body = std::move(*loaded.body);
    } catch (const evo::ValidationError& e) {
        return report_problems(e.problems);
    }

    const double total_s = args.get_double("--seconds", evo::evaluation_seconds(experiment));
    const double settle_s = experiment.simulation.settle_s;
    const double record_fps = experiment.simulation.record_fps;

    std::shared_ptr<const engine::Model> model;
    try {
        const evo::Body framed = evo::apply_frame_and_overrides(experiment, body);
        model = evo::model_of(experiment, framed, phase_seed);
    } catch (const std::invalid_argument& e) {
        throw std::runtime_error(body_path + ": cannot simulate: " + e.what());
    }
    const std::string budget = simulation_seconds_problem(*model, experiment, total_s);
    if (!budget.empty()) throw std::runtime_error(experiment_path + ": " + budget);
    engine::StagedFolder staged(out_dir, simulate_output);

    SimulationRecorder recorder(*model, settle_s);
    ProgressLine progress(stderr, total_s, model->voxel_count(), ::isatty(STDERR_FILENO) != 0);
    // The whole run is recorded (a replay shows every second); beside it, where an evaluation of
    // this body would have ended because the motion repeats (evo/evaluate/periodic_end.hpp) and
    // how far its extrapolated measures are from the ones measured here.
    evo::Experiment timed = experiment;
    if (total_s > settle_s) timed.simulation.evaluate_s = total_s - settle_s;
    const engine::World at_start(model);
    evo::MeasureTracker extrapolated(timed, at_start);
    evo::PeriodicEnd periodic(timed, model->dt_s(), evo::TrackSampler(timed, at_start).groups(),
                              evo::every_part_held(*model));
    // And where its settling would have stopped being integrated, the body at rest
    // (evo/evaluate/settle_rest.hpp; it resumes at settle_s).
    evo::SettleRest settle(timed, evo::TrackSampler(timed, at_start).groups(),
                           evo::every_part_held(*model));
    bool rested = false;
    double rest_stop_s = settle_s;
    bool repeated = false;
    double would_stop_s = total_s;
    evo::SimulationOptions options;
    options.seconds = total_s;
    options.end_early = false;
    evo::SimulationHooks hooks;
    hooks.record = [&](const engine::World& w) {
        recorder.observe(w);
        progress.update(w.time_s(), w.steps());
    };
    hooks.sampled = [&](const evo::TrackSample& sample) {
        if (!rested && settle.observe(sample)) {
            rested = true;
            rest_stop_s = sample.t_s;
        }
        if (repeated) return;
        extrapolated.observe(sample);
        if (periodic.observe(sample)) {
            repeated = true;
            would_stop_s = sample.t_s;
            periodic.extrapolate(
                [&](const evo::TrackSample& later) { extrapolated.observe(later); });
        }
    };
    const auto start = std::chrono::steady_clock::now();
    const evo::SimulationResult sim = evo::simulate(experiment, model, options, hooks);
    const double wall_s =
        std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
    progress.finish();

    const RunStats stats = run_stats_of(*model, sim.world, wall_s);
    const DisplacementSummary displacements =
        summarize_displacements(recorder.samples(), settle_s, model->voxel_size_m());

    nlohmann::ordered_json summary = summary_json(stats, displacements);
    summary["experiment"] = experiment_path;
    summary["body"] = body_path;
    summary["settle_s"] = settle_s;
    summary["requested_s"] = total_s;
    summary["record_fps"] = record_fps;
    summary["samples"] = recorder.samples().size();
    summary["voxel_size_m"] = model->voxel_size_m();
    // Through text: exploits_to_json builds the unordered json type.
    summary["exploits"] =
        nlohmann::ordered_json::parse(evo::exploits_to_json(sim.report.exploits).dump());

    evo::FitnessReport full_report, early_report;
    full_report.measures = sim.report.measures;
    early_report.measures = extrapolated.measures();
    nlohmann::ordered_json early = {{"applies", periodic.enabled()},
                                    {"ends_early", repeated && !stats.diverged},
                                    {"stop_s", would_stop_s},
                                    {"periodic_residual", periodic.residual_voxels()}};
    if (repeated && !stats.diverged) {
        for (std::size_t m = 0; m < full_report.measures.size(); ++m)
            early["extrapolated"][evo::kFitnessNames[m]] = early_report.measures[m];
        early["gate_error"] = evo::periodic_end_error(early_report, full_report);
    }
    summary["periodic_end"] = early;
    summary["settle_rest"] = {{"applies", settle.enabled()},
                              {"ends_early", rested && !stats.diverged},
                              {"stop_s", rest_stop_s},
                              {"resume_s", settle_s}};

    try {
        engine::write_replay(staged.file("replay.bin"), recorder.replay());
        evo::write_file_atomically(staged.file("trajectory.csv"),
                                   trajectory_csv(recorder.samples()));
        evo::write_file_atomically(staged.file("summary.json"), summary.dump(2) + "\n");
    } catch (const std::runtime_error& e) {
        throw std::runtime_error(staged.as_final(e.what()));
    }
    staged.commit();

    if (stats.diverged) {
        std::cerr << "bhm simulate: the simulation diverged at t = " << stats.sim_time_s
                  << " s: " << stats.divergence_reason << "\n";
    }
    char line[320];
    std::snprintf(line, sizeof line,
                  "%d voxels, %.3g s simulated in %.3g s (%.3g voxel-steps/s)%s; centre of mass "
                  "moved %.4g voxels (YZ %.4g); wrote ",
                  stats.voxels, stats.sim_time_s, stats.wall_s, stats.voxel_steps_per_s(),
                  stats.diverged ? ", DIVERGED" : "", displacements.displacement_3d_voxels,
                  displacements.displacement_yz_voxels);
    std::cout << line << out_dir << std::endl;
    return stats.diverged ? kExitDiverged : 0;
}

}  // namespace

int cmd_simulate(const Args& args) {
    ArgParser parser("simulate", "EXPERIMENT.json --body BODY.json [--seconds T] [--out DIR]",
                     kSummary);
    parser.positional("EXPERIMENT.json", "the experiment (docs/experiment-format.md)")
        .option("--body", "BODY.json", "the body to simulate (required)")
        .option("--seconds", "T", "total simulated seconds (default: settle_s + evaluate_s)")
        .option("--out", "DIR", "output directory, replaced whole (default: ./sim-out)",
                PathRole::OutputDir)
        .option("--phase-seed", "N",
                "seed of the per-voxel actuation phases when the experiment's phase is random "
                "(default 0)");
    return run_command(parser, args, simulate);
}

}  // namespace bhm::app
