// bhm calibrate: fit simulation parameters to a measured track (evo/calibrate/calibrator.hpp) and
// write the report, the calibrated experiment, the simulated tracks and a plot. This file only
// wires files to the fit.
#include <unistd.h>

#include <cmath>
#include <cstdio>
#include <filesystem>
#include <iostream>
#include <memory>
#include <nlohmann/json.hpp>
#include <stdexcept>
#include <string>

#include "app/cli/arg_parser.hpp"
#include "app/cli/commands.hpp"
#include "app/cli/evolve_cluster.hpp"
#include "app/cli/problem_report.hpp"
#include "app/cli/simulation_limits.hpp"
#include "app/cli/track_plot.hpp"
#include "engine/io/staged_folder.hpp"
#include "evo/calibrate/calibrator.hpp"
#include "evo/calibrate/fit_parameters.hpp"
#include "evo/calibrate/measured_track.hpp"
#include "evo/calibrate/track_simulation.hpp"
#include "evo/evaluate/simulate.hpp"
#include "evo/evaluate/worker_pool.hpp"
#include "evo/experiment/body_spec_of.hpp"
#include "evo/experiment/experiment_io.hpp"

namespace bhm::app {

namespace {

const char* const kSummary =
    "Finds the simulation parameters named by --fit that make BODY under EXPERIMENT move as the\n"
    "measured TRACK does (docs/track-format.md, docs/calibration.md): a parallel scan, then\n"
    "NLopt's BOBYQA with restarts, then damped Gauss-Newton steps from its result (taken\n"
    "only where the misfit drops), bounded to 1/5..5 times the\n"
    "experiment's value (phase_lag: -pi..pi; a muscle's rise_s, decay_s, contraction_strain also\n"
    "within their fields' ranges), minimising the RMS difference of the displacements\n"
    "from the first row at the track's times (parameters: see --fit; the sine model's and the\n"
    "muscle model's apply only to an experiment whose materials use that model). Writes into DIR:\n"
    "  report.json                 fitted values with one standard deviation (from the misfit's\n"
    "                              curvature at the optimum, Gauss-Newton), misfit before/after,\n"
    "                              simulations used, the polish's steps, correlations,\n"
    "                              parameters that trade off,\n"
    "                              and warnings (poor fit, a bound reached)\n"
    "  calibrated-experiment.json  EXPERIMENT with the fitted values\n"
    "  simulated-before.csv, simulated-after.csv  the simulated points at the track's times\n"
    "                              (track format, metres)\n"
    "  tracks.png                  per point and axis, displacement against time: measured =\n"
    "                              black dots, before = orange, after = blue\n"
    "With --simulate-only, only simulated.csv (the experiment as given; no --fit needed).\n"
    "\n"
    "exit status: 0 ok (a poor fit is reported in report.json and on stderr), 1 invalid input or\n"
    "a build without NLopt, 2 usage error.";

nlohmann::json finite_or_null(double v) {
    return std::isfinite(v) ? nlohmann::json(v) : nlohmann::json(nullptr);
}

// What bhm calibrate writes into its --out folder, which is replaced whole
// (engine/io/staged_folder.hpp): a kill or a failed write leaves the old report whole (issue 41 R5).
bool calibrate_output(const std::string& name) {
    return name == "report.json" || name == "calibrated-experiment.json" ||
           name == "simulated.csv" || name == "simulated-before.csv" ||
           name == "simulated-after.csv" || name == "tracks.png";
}

// Runs write, naming the --out folder's file instead of its staging copy in an error.
template <class Write>
void staged_write(const engine::StagedFolder& staged, Write&& write) {
    try {
        write();
    } catch (const std::runtime_error& e) {
        throw std::runtime_error(staged.as_final(e.what()));
    }
}

// The simulated points as a track file (absolute positions, metres).
std::string simulated_csv(const evo::MeasuredTrack& track, const evo::SimulatedTrack& sim,
                          const std::string& comment) {
    evo::MeasuredTrack out = track;
    for (std::size_t i = 0; i < out.points.size(); ++i) out.points[i].position_m = sim.position_m[i];
    out.t_s.resize(sim.position_m.empty() ? 0 : sim.position_m[0].size());
    return evo::measured_track_to_csv(out, comment);
}

nlohmann::json report_json(const evo::CalibrationResult& r, const std::string& experiment_path,
                           const std::string& body_path, const std::string& track_path,
                           int threads) {
    nlohmann::json fit = nlohmann::json::array();
    for (const auto& f : r.fitted)
        fit.push_back({{"name", f.parameter.name},
                       {"unit", evo::fit_unit(f.parameter)},
                       {"initial", f.initial_value},
                       {"fitted", f.value},
                       {"sigma", finite_or_null(f.sigma)},
                       {"relative_sigma",
                        finite_or_null(f.value != 0.0 ? f.sigma / std::abs(f.value) : NAN)},
                       {"at_bound", f.at_bound}});
    const auto& id = r.identifiability;
    nlohmann::json correlation = nlohmann::json::array();
    for (const auto& row : id.correlation) {
        nlohmann::json line = nlohmann::json::array();
        for (double c : row) line.push_back(finite_or_null(c));
        correlation.push_back(line);
    }
    nlohmann::json trade_offs = nlohmann::json::array();
    for (const auto& group : id.trade_offs) {
        nlohmann::json names = nlohmann::json::array();
        for (int i : group) names.push_back(r.fitted[static_cast<std::size_t>(i)].parameter.name);
        trade_offs.push_back(names);
    }
    nlohmann::json no_effect = nlohmann::json::array();
    for (int i : id.no_effect) no_effect.push_back(r.fitted[static_cast<std::size_t>(i)].parameter.name);
    return {{"experiment", experiment_path},
            {"body", body_path},
            {"track", track_path},
            {"fit", fit},
            {"phase_lag_rad", r.calibrated.phase_lag_rad},
            {"misfit_before_m", finite_or_null(r.misfit_before_m)},
            {"misfit_after_m", finite_or_null(r.misfit_after_m)},
            {"motion_rms_m", r.motion_rms_m},
            {"relative_misfit_after",
             finite_or_null(r.motion_rms_m > 0 ? r.misfit_after_m / r.motion_rms_m : NAN)},
            {"good_fit", r.good_fit},
            {"simulations",
             {{"optimiser", r.optimiser_simulations},
              {"uncertainty", r.jacobian_simulations},
              {"optimiser_passes", r.optimiser_passes},
              {"scan", r.scan_simulations},
              {"polish", r.polish_simulations},
              {"before_after", 2},
              {"total", r.optimiser_simulations + r.jacobian_simulations + 2}}},
            {"stop_reason", r.stop_reason},
            {"polish",
             {{"steps", r.polish_steps},
              {"simulations", r.polish_simulations},
              {"misfit_before_m", finite_or_null(r.misfit_before_polish_m)},
              {"misfit_after_m", finite_or_null(r.misfit_after_m)},
              {"stop_reason", r.polish_stop}}},
            {"identifiability",
             {{"correlation", correlation},
              {"smallest_scaled_curvature_eigenvalue", id.smallest_eigenvalue},
              {"near_singular", id.near_singular},
              {"trade_offs", trade_offs},
              {"no_effect", no_effect}}},
            {"warnings", r.warnings},
            {"threads", threads},
            {"wall_s", r.wall_s}};
}

// Every simulation of the calibration runs from 0 to the track's end: refused up front by the
// rule bhm simulate obeys (app/cli/simulation_limits.hpp), where a track at time_offset_s 1e6 ran
// for hours with no output (issue 41 R1). Checked at the experiment's own parameters, which the
// before simulation runs: a trial of the fit scales E and density by at most 5 each way
// (fit_parameters.cpp), so its step, sqrt(density / E), is at most 5 times shorter.
void refuse_track_over_budget(const evo::Experiment& experiment, const evo::Body& framed,
                              const std::string& body_path, const evo::MeasuredTrack& track) {
    std::shared_ptr<const engine::Model> model;
    try {
        model = evo::model_of(experiment, framed);
    } catch (const std::invalid_argument& e) {
        throw std::runtime_error(body_path + ": cannot simulate: " + e.what());
    }
    if (const std::string why = track_budget_problem(*model, experiment, track); !why.empty())
        throw std::runtime_error(why);
}

//! Set by cmd_calibrate for the command's duration: the MPI ranks when started by mpirun.
EvolveCluster* g_cluster = nullptr;

int calibrate(ArgParser& args) {
    const std::string experiment_path = args.positionals().at(0);
    if (!args.has("--body")) throw UsageError("missing --body BODY.json");
    if (!args.has("--track")) throw UsageError("missing --track TRACK.csv");
    const bool simulate_only = args.has("--simulate-only");
    if (!simulate_only && !args.has("--fit")) throw UsageError("missing --fit NAMES");
    const long long max_sims = args.get_int("--max-simulations", 200);
    if (max_sims < 1) throw UsageError("--max-simulations must be >= 1");
    const long long threads_arg = args.get_int("--threads", 0);
    if (threads_arg < 0) throw UsageError("--threads must be >= 0");
    const std::string body_path = args.get("--body"), track_path = args.get("--track");
    const std::string out_dir = args.get("--out", "calibrate-out");

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
    const evo::MeasuredTrack track = evo::load_measured_track(track_path);
    const evo::Body framed = evo::apply_frame_and_overrides(experiment, body);
    // Said before anything runs: a track in milliseconds started simulations 1000 times the
    // experiment's length without a word (issue 41 R1).
    const std::string span_warning = evo::track_span_warning(track, experiment);
    if (!span_warning.empty()) std::cerr << "warning: " << span_warning << "\n";
    refuse_track_over_budget(experiment, framed, body_path, track);
    if (simulate_only) {
        engine::StagedFolder staged(out_dir, calibrate_output);
        const auto sim = evo::simulate_track(evo::FitPoint{experiment, 0.0}, framed, track);
        staged_write(staged, [&] {
            evo::write_file_atomically(
                staged.file("simulated.csv"),
                simulated_csv(track, sim,
                              "Simulated by bhm calibrate --simulate-only: " + experiment_path +
                                  ", " + body_path + ", at the times of " + track_path));
        });
        staged.commit();
        std::cout << "wrote " << out_dir << "/simulated.csv" << (sim.diverged ? " (diverged)" : "")
                  << "\n";
        return sim.diverged ? 1 : 0;
    }
    std::vector<evo::FitParameter> parameters;
    try {
        parameters = evo::parse_fit_list(args.get("--fit"), experiment);
    } catch (const std::runtime_error& e) {
        throw UsageError(e.what());
    }
    if (!evo::calibration_available())
        throw std::runtime_error("bhm was built without NLopt (Debian's libnlopt-cxx-dev), so it "
                                 "cannot calibrate");
    // Before any simulation: a folder that cannot be written costs nothing.
    engine::StagedFolder staged(out_dir, calibrate_output);

    evo::CalibrationOptions options;
    options.threads = evo::resolve_thread_count(static_cast<int>(threads_arg));
    options.max_simulations = static_cast<int>(max_sims);
    const bool tty = ::isatty(STDERR_FILENO) != 0;
    options.progress = [&](int sims, double best) {
        if (tty)
            std::fprintf(stderr, "\rcalibrate: %d simulations, best misfit %.4g m   ", sims, best);
        else if (sims % 20 == 0)
            std::fprintf(stderr, "calibrate: %d simulations, best misfit %.4g m\n", sims, best);
    };
    if (g_cluster && g_cluster->size() > 1) {
        // Under mpirun: the scan's and the Jacobian's simulations spread over the ranks
        // (docs/cluster.md); each rank rebuilds the fit from the same setup, so results are
        // those of one process, bit for bit.
        evo::TrackSetupMessage setup;
        setup.requested_threads = static_cast<std::int32_t>(threads_arg);
        setup.fit_list = args.get("--fit");
        setup.experiment = experiment;
        setup.framed_body = framed;
        setup.track = track;
        options.batches = g_cluster->connect_calibration(options.threads, setup);
        std::cerr << "bhm calibrate: " << g_cluster->describe() << "\n";
    }
    const evo::CalibrationResult r =
        evo::calibrate(experiment, framed, track, parameters, options);
    if (tty) std::fprintf(stderr, "\n");

    evo::Experiment calibrated = r.calibrated.experiment;
    calibrated.description += (calibrated.description.empty() ? "" : " ") +
                              std::string("Calibrated by bhm calibrate against ") + track_path +
                              " (" + out_dir + "/report.json).";
    auto report = report_json(r, experiment_path, body_path, track_path, options.threads);
    if (!span_warning.empty()) report["warnings"].push_back(span_warning);
    staged_write(staged, [&] {
        evo::save_experiment(staged.file("calibrated-experiment.json"), calibrated);
        evo::write_file_atomically(staged.file("simulated-before.csv"),
                                   simulated_csv(track, r.before, "Simulated before calibration"));
        evo::write_file_atomically(staged.file("simulated-after.csv"),
                                   simulated_csv(track, r.after, "Simulated after calibration"));
        if (track_plot_available()) {
            write_track_plot(staged.file("tracks.png"), track, r.before, r.after);
            report["plot"] = "tracks.png";
        } else {
            report["plot"] = nullptr;
            report["warnings"].push_back("no plot: bhm was built without libpng");
        }
        evo::write_file_atomically(staged.file("report.json"), report.dump(2) + "\n");
    });
    staged.commit();

    for (const auto& f : r.fitted)
        std::cout << f.parameter.name << " = " << f.value << " +- " << f.sigma << " "
                  << evo::fit_unit(f.parameter) << " (was " << f.initial_value << ")\n";
    std::cout << "misfit " << r.misfit_before_m << " m -> " << r.misfit_after_m << " m (track motion "
              << r.motion_rms_m << " m), " << r.optimiser_simulations + r.jacobian_simulations + 2
              << " simulations, " << r.wall_s << " s\n";
    std::cout << "Gauss-Newton polish: " << r.polish_steps << " step"
              << (r.polish_steps == 1 ? "" : "s") << ", " << r.polish_simulations
              << " simulations, misfit " << r.misfit_before_polish_m << " m -> "
              << r.misfit_after_m << " m (" << r.polish_stop << ")\n";
    for (const auto& w : report["warnings"])
        if (w != span_warning) std::cerr << "warning: " << w.get<std::string>() << "\n";  // said up front
    std::cout << "wrote " << out_dir << "/report.json\n";
    return 0;
}

}  // namespace

int cmd_calibrate(const Args& args) {
    ArgParser parser("calibrate",
                     "EXPERIMENT.json --body BODY.json --track TRACK.csv --fit NAMES [--out DIR]",
                     kSummary);
    parser.positional("EXPERIMENT.json", "the experiment (docs/experiment-format.md)")
        .option("--body", "BODY.json", "the body the track was measured on (required)")
        .option("--track", "TRACK.csv", "the measured track (docs/track-format.md; required)")
        .option("--fit", "NAMES", "comma-separated parameters to fit: " + evo::fit_names_help())
        .option("--out", "DIR", "output directory, replaced whole (default: ./calibrate-out)",
                PathRole::OutputDir)
        .option("--threads", "N",
                "simulations at once in the scan and the uncertainty (default: all cores)")
        .option("--max-simulations", "N",
                "budget of the scan's, the optimiser's and the Gauss-Newton polish's "
                "simulations (default 200; the polish gets what the optimiser leaves)")
        .flag("--simulate-only", "only simulate the experiment as given at the track's times");
    // Under mpirun every rank but 0 only simulates what rank 0 sends (docs/cluster.md).
    std::unique_ptr<EvolveCluster> cluster;
    try {
        cluster = EvolveCluster::join();
    } catch (const std::exception& e) {
        std::cerr << "bhm calibrate: " << e.what() << "\n";
        return 1;
    }
    if (cluster->rank() > 0) return cluster->serve_calibration();
    g_cluster = cluster.get();
    const int status = run_command(parser, args, calibrate);
    g_cluster = nullptr;
    return status;
}

}  // namespace bhm::app
