// bhm evolve: a headless AFPO run (evo::EvolutionRun) with a progress line, Ctrl-C handling and
// --resume. Everything else lives in evo/; this file only wires it to the command line.
#include <atomic>
#include <csignal>
#include <cstdio>
#include <filesystem>
#include <iostream>
#include <memory>
#include <string>

#include "app/cli/arg_parser.hpp"
#include "app/cli/commands.hpp"
#include "app/cli/evolve_cluster.hpp"
#include "app/cli/path_checks.hpp"
#include "app/cli/problem_report.hpp"
#include "evo/experiment/experiment_io.hpp"
#include "evo/run/batch.hpp"
#include "evo/run/checkpoint.hpp"
#include "evo/run/evolution_run.hpp"
#include "evo/verify/continuum_checker.hpp"

namespace bhm::app {

namespace {

const char* const kSummary =
    "Evolves morphologies for EXPERIMENT with AFPO over CPPNs (paper section 3) and writes into "
    "DIR:\n"
    "  run.json                 experiment, seed, version, rule changes\n"
    "  fitness.csv              generation, evaluations, simulations, best_fitness, "
    "median_fitness,\n"
    "                           best_age, best_id, diverged, wall_s (counts per generation),\n"
    "                           best_escaped, best_detached_motion, best_tentacle, "
    "flagged_members\n"
    "                           (exploit flags), ended_early, mean_simulated_s, best_simulated_s,\n"
    "                           best_periodic_residual (early ends; docs/evolution.md); NEAT adds\n"
    "                           species, novelty\n"
    "                           search best_novelty, median_novelty, archive_size, archive_added,\n"
    "                           archive_threshold, champion_fitness\n"
    "  population.csv           the population after the last generation: fitness, age,\n"
    "                           voxels (volume), active voxels, Pareto rank\n"
    "  champion.json            genome, phenotype layers, fitness, generation found\n"
    "  champions/gen-NNNNN.json every new champion\n"
    "  champion.vxa             the champion for VoxCAD (VXA 1.0)\n"
    "  checkpoint.json          after every generation (previous one: checkpoint.prev.json)\n"
    "Stops at the generation or wall-time budget (experiment's evolution settings unless given),\n"
    "or cleanly on Ctrl-C / SIGTERM: the generation in progress is abandoned and the last\n"
    "checkpoint kept; --resume continues exactly where it stopped. The same seed gives the same\n"
    "run whatever --threads is.\n"
    "Under mpirun/srun, rank 0 evolves and every rank simulates with --threads threads; the run\n"
    "is the same whatever the number of ranks (docs/cluster.md).\n"
    "exit status: 0 done or stopped, 1 invalid input or failure, 2 usage error, 3 an MPI rank\n"
    "died or hung (the last complete generation is checkpointed: --resume it with any ranks).";

constexpr int kExitRankLost = 3;

// The one piece of global state: where the signal handler raises the stop request.
std::atomic<bool>* g_stop_flag = nullptr;
// The ranks this process belongs to (just itself without mpirun), for evolve() below.
EvolveCluster* g_cluster = nullptr;

extern "C" void handle_stop_signal(int) {
    if (g_stop_flag) g_stop_flag->store(true);
}

void install_stop_handlers(std::atomic<bool>& flag) {
    static_assert(std::atomic<bool>::is_always_lock_free,
                  "the signal handler needs a lock-free flag");
    g_stop_flag = &flag;
    struct sigaction action {};
    action.sa_handler = handle_stop_signal;
    sigemptyset(&action.sa_mask);
    action.sa_flags = SA_RESETHAND;  // a second Ctrl-C ends the process at once
    sigaction(SIGINT, &action, nullptr);
    sigaction(SIGTERM, &action, nullptr);
}

void restore_default_handlers() {
    std::signal(SIGINT, SIG_DFL);
    std::signal(SIGTERM, SIG_DFL);
    g_stop_flag = nullptr;
}

std::string clock_text(double seconds) {
    if (seconds < 0) return "?";
    const long long s = static_cast<long long>(seconds + 0.5);
    char buffer[32];
    std::snprintf(buffer, sizeof buffer, "%lld:%02lld:%02lld", s / 3600, (s / 60) % 60, s % 60);
    return buffer;
}

//! Novelty search's part of the progress line: novelty, archive, the champion's fitness.
std::string novelty_text(const evo::GenerationReport& r) {
    if (!r.novelty) return "";
    char buffer[160];
    std::snprintf(buffer, sizeof buffer, "  novelty %.4g  archive %d (+%d)  champion %.6g",
                  r.novelty->best_novelty, r.novelty->archive_size, r.novelty->archive_added,
                  r.novelty->champion_fitness);
    return buffer;
}

void print_progress(const evo::GenerationReport& r) {
    std::fprintf(
        stderr,
        "gen %d/%d  best %.6g%s  median %.6g  sims %d (%.2f/s)  diverged %d%s%s  elapsed %s  "
        "eta %s\n",
        r.generation, r.generation_budget - 1, r.best_fitness, r.new_champion ? " *" : "",
        r.median_fitness, r.simulations, r.simulations_per_s, r.diverged,
        r.species > 0 ? ("  species " + std::to_string(r.species)).c_str() : "",
        novelty_text(r).c_str(),
        clock_text(r.elapsed_s).c_str(), clock_text(r.eta_s).c_str());
}

//! --runs N: a batch of N runs in DIR/run-NN plus DIR/batch.csv (evo/run/batch.hpp).
int evolve_batch(const evo::Experiment& experiment, const evo::RunOptions& options, int runs,
                 bool resume) {
    if (g_cluster && g_cluster->size() > 1) {
        std::cerr << "bhm evolve: --runs runs its runs in one process; under mpirun start one "
                     "run per job instead\n";
        g_cluster->abort(1);
    }
    evo::BatchOptions batch_options;
    batch_options.out_dir = options.out_dir;
    batch_options.runs = runs;
    batch_options.run = options;
    evo::BatchRun batch(experiment, batch_options, resume);
    for (const auto& w : batch.warnings())
        std::cerr << "bhm evolve: warning: " << w << "\n";
    std::cerr << "bhm evolve: " << experiment.name << " -> " << options.out_dir << ", " << runs
              << " runs, seeds " << batch.base_seed() << ".." << batch.base_seed() + runs - 1
              << (resume ? " (resuming)" : "") << "\n";
    batch.set_report_callback([](int run, std::shared_ptr<const evo::GenerationReport> r) {
        std::fprintf(stderr, "run %02d: ", run);
        print_progress(*r);
    });
    install_stop_handlers(batch.stop_flag());
    evo::StopReason reason;
    try {
        reason = batch.run();
    } catch (...) {
        restore_default_handlers();
        throw;
    }
    restore_default_handlers();
    std::cerr << "bhm evolve: "
              << (reason == evo::StopReason::StopRequested
                      ? "stopped; continue the batch with --resume"
                      : "batch done")
              << "; " << options.out_dir << "/" << evo::kBatchCsvFile << "\n";
    return 0;
}

int evolve(ArgParser& args) {
    const std::string experiment_path = args.positionals().at(0);
    if (!args.has("--out")) throw UsageError("missing --out DIR");
    evo::RunOptions options;
    options.out_dir = args.get("--out");
    options.writer = "bhm evolve";
    // evolution.verify's checks (CalculiX beside the simulations; under MPI on this, the
    // coordinating, process while the ranks simulate).
    options.checker = std::make_shared<evo::CalculixChecker>();
    if (args.has("--resume")) {
        check_existing_dir("--out", options.out_dir);
        // A run file replaced by a folder would fail only when first rewritten, a whole
        // generation later: refuse it now.
        for (const char* name : {evo::kCheckpointFile, evo::kPreviousCheckpointFile, "fitness.csv",
                                 "population.csv", "champion.json", "run.json"}) {
            const auto file = std::filesystem::path(options.out_dir) / name;
            std::error_code ec;
            const auto status = std::filesystem::symlink_status(file, ec);
            if (std::filesystem::exists(status) && !std::filesystem::is_regular_file(status))
                throw std::runtime_error(file.string() +
                                         ": is not a regular file (a folder?); the run rewrites "
                                         "it each generation: move it away, then --resume");
        }
    }
    if (args.has("--generations")) {
        const long long n = args.get_int("--generations", 0);
        if (n < 1 || n > 100000000) throw UsageError("--generations must be in [1, 1e8]");
        options.generations = static_cast<int>(n);
    }
    if (args.has("--hours")) {
        const double h = args.get_double("--hours", 0.0);
        if (!(h > 0.0)) throw UsageError("--hours must be positive");
        options.wall_budget_h = h;
    }
    if (args.has("--seed")) {
        const long long s = args.get_int("--seed", 0);
        if (s < 0) throw UsageError("--seed must be >= 0");
        options.seed = static_cast<std::uint64_t>(s);
    }
    if (args.has("--threads")) {
        const long long t = args.get_int("--threads", 0);
        if (t < 0 || t > 1024) throw UsageError("--threads must be in [0, 1024] (0 = all cores)");
        options.threads = static_cast<int>(t);
    }
    ClusterSettings cluster;
    if (args.has("--rank-timeout")) {
        cluster.rank_timeout_s = args.get_double("--rank-timeout", 0.0);
        if (!(cluster.rank_timeout_s > 0.0)) throw UsageError("--rank-timeout must be positive");
    }

    evo::Experiment experiment;
    try {
        experiment = evo::load_experiment(experiment_path);
        say_library_warnings(experiment);
        // --body B.json: evolve only a controller for that body (evolution.controller fixed_body;
        // issue 44). The body is kept in the experiment, so run.json and a resume have it.
        if (args.has("--body")) {
            if (args.has("--resume"))
                throw UsageError(
                    "--body starts a run: a resumed run keeps the body it started with");
            auto& controller = experiment.evolution.controller;
            if (controller.mode != evo::ControllerMode::None &&
                controller.mode != evo::ControllerMode::FixedBody)
                throw UsageError("--body evolves a controller for a fixed body, but " +
                                 experiment_path + " sets evolution.controller.mode to \"" +
                                 evo::kControllerModeNames[static_cast<int>(controller.mode)] +
                                 "\"");
            controller.mode = evo::ControllerMode::FixedBody;
            controller.body = evo::load_body(args.get("--body"));
            auto problems = evo::validate_experiment(experiment, experiment_path);
            if (!problems.empty()) throw evo::ValidationError(std::move(problems));
        }
    } catch (const evo::ValidationError& e) {
        return report_problems(e.problems);
    }

    if (args.has("--runs")) {
        const long long n = args.get_int("--runs", 0);
        if (n < 1 || n > 99) throw UsageError("--runs must be in [1, 99]");
        return evolve_batch(experiment, options, static_cast<int>(n), args.has("--resume"));
    }

    std::unique_ptr<evo::EvolutionRun> run;
    if (args.has("--resume")) {
        run = evo::EvolutionRun::resume(options);
        for (const auto& w : run->resume_warnings())
            std::cerr << "bhm evolve: warning: " << w << "\n";
        if (run->experiment().name != experiment.name)
            std::cerr << "bhm evolve: warning: " << experiment_path << " is '" << experiment.name
                      << "' but the run in " << options.out_dir << " is '" << run->experiment().name
                      << "'; continuing with the run's own experiment\n";
        std::cerr << "bhm evolve: resuming " << options.out_dir << " after generation "
                  << run->state().generation << " (seed " << run->state().seed << ")\n";
    } else {
        run = std::make_unique<evo::EvolutionRun>(experiment, options);
        std::cerr << "bhm evolve: " << experiment.name << " -> " << options.out_dir << " (seed "
                  << run->state().seed << ", population " << experiment.evolution.population << ", "
                  << run->threads() << " threads)\n";
    }
    cluster.local_threads = run->threads();
    cluster.requested_threads = options.threads.value_or(run->experiment().evolution.threads);
    std::shared_ptr<evo::Evaluator> evaluator;
    try {
        evaluator = g_cluster->connect(cluster);
    } catch (const evo::EvaluatorLost& e) {
        std::cerr << "bhm evolve: " << e.what() << "\n";
        return kExitRankLost;
    }
    if (evaluator) {
        run->set_evaluator(std::move(evaluator));
        std::cerr << "bhm evolve: " << g_cluster->describe() << "\n";
    }
    run->set_report_callback(
        [](std::shared_ptr<const evo::GenerationReport> r) { print_progress(*r); });

    install_stop_handlers(run->stop_flag());
    evo::StopReason reason;
    try {
        reason = run->run();
    } catch (const evo::EvaluatorLost& e) {
        restore_default_handlers();
        const int g = run->state().generation;
        std::cerr << "bhm evolve: " << e.what() << "; generation " << g + 1 << " abandoned; "
                  << (g >= 0 ? "the checkpoint of generation " + std::to_string(g) + " (" +
                                   run->checkpoint_path() +
                                   ") is complete: continue with --resume, on any number of "
                                   "ranks"
                             : std::string("no generation completed, nothing to resume"))
                  << "\n";
        return kExitRankLost;
    } catch (...) {
        restore_default_handlers();
        throw;
    }
    restore_default_handlers();

    const auto& state = run->state();
    switch (reason) {
        case evo::StopReason::GenerationBudget:
            std::cerr << "bhm evolve: generation budget reached (" << run->generation_budget()
                      << ")\n";
            break;
        case evo::StopReason::WallBudget:
            std::cerr << "bhm evolve: wall-time budget reached ("
                      << clock_text(run->wall_budget_s()) << ")\n";
            break;
        case evo::StopReason::StopRequested: {
            // The abandoned generation's time stays on the clock, in the checkpoint too (as the
            // studio's Stop does): a resumed run's elapsed time goes on from here, not back.
            try {
                run->keep_stopped_time();
            } catch (const std::exception& e) {
                std::cerr << "bhm evolve: warning: the stopped generation's time is not in the "
                             "checkpoint: "
                          << e.what() << "\n";
            }
            // Say only what is on disk: the checkpoint of the last complete generation, if any.
            std::error_code ec;
            const std::string& checkpoint = run->checkpoint_path();
            const bool saved =
                !checkpoint.empty() && std::filesystem::is_regular_file(checkpoint, ec);
            const bool abandoned = run->progress().generation > state.generation;
            std::cerr << "bhm evolve: stopped; "
                      << (abandoned ? "generation " + std::to_string(state.generation + 1) +
                                          " abandoned (it runs again on resume); "
                                    : std::string())
                      << (saved ? "last complete generation " + std::to_string(state.generation) +
                                      " is in " + checkpoint + " (continue with --resume)"
                                : std::string("no generation completed, nothing to resume"))
                      << "\n";
            break;
        }
    }
    if (state.champion)
        std::cout << "champion: id " << state.champion->individual.id << ", fitness "
                  << state.champion->individual.report.fitness << " ("
                  << evo::kFitnessNames[static_cast<std::size_t>(state.experiment.fitness.measure)]
                  << "), found in generation " << state.champion->generation_found << "; "
                  << options.out_dir << "/champion.json, champion.vxa\n";
    return 0;
}

}  // namespace

int cmd_evolve(const Args& args) {
    ArgParser parser("evolve", "EXPERIMENT.json --out DIR [OPTIONS]", kSummary);
    parser.positional("EXPERIMENT.json", "the experiment file (docs/experiment-format.md)")
        .option("--out", "DIR", "run directory (created; must not hold a run unless --resume)",
                PathRole::OutputDir)
        .option("--generations", "N",
                "total generations including generation 0 (default: experiment's)")
        .option("--hours", "H", "wall-time budget in hours, across resumes (default: experiment's)")
        .option("--seed", "S", "random seed (default: experiment's evolution.seed)")
        .option("--threads", "T",
                "simulation threads (per MPI rank), 0 = all cores (default: experiment's)")
        .option("--rank-timeout", "S",
                "under MPI: seconds a rank holding bodies may stay silent before it is declared "
                "lost (default 60)")
        .option("--runs", "N",
                "a batch of N independent runs (seeds S..S+N-1) in DIR/run-01.. plus "
                "DIR/batch.csv: each run's best per generation, mean and 95 % interval")
        .option("--body", "B.json",
                "evolve only a controller for this body (evolution.controller fixed_body; "
                "docs/experiment-format.md)")
        .flag("--resume", "continue the run (or with --runs, the batch) in DIR");
    std::unique_ptr<EvolveCluster> cluster;
    try {
        cluster = EvolveCluster::join();
    } catch (const std::exception& e) {
        std::cerr << "bhm evolve: " << e.what() << "\n";
        return 1;
    }
    if (cluster->rank() > 0) {
        try {
            return cluster->serve();
        } catch (const std::exception& e) {
            std::cerr << "bhm evolve (rank " << cluster->rank() << "): " << e.what() << "\n";
            return 1;
        }
    }
    g_cluster = cluster.get();
    const int status = run_command(parser, args, evolve);
    g_cluster = nullptr;
    // A hung rank would never finish: end them all (the checkpoint is already on disk).
    if (status == kExitRankLost) cluster->abort(status);
    return status;
}

}  // namespace bhm::app
