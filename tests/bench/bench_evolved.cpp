// bench_evolved: what a generation of an evolved population costs (issue 42), beside generation 0.
// For each preset, the checkpoint tests/bench/evolved/<preset>.checkpoint.json (a run of the
// preset with a small population, at generation >= 20; tests/bench/make_evolved.sh) is copied
// into a scratch run directory and resumed for one generation, and a fresh run of the same
// experiment and seed computes its generation 0. Both run the preset's full settings (1 s + 10 s,
// the early end on) through the evolution loop itself (EvolutionRun: breeding, the cache,
// simulations, selection, checkpoint), on --threads simulation threads. CPU seconds are the
// process's (every thread), so a shared machine's load does not enter them.
// One CSV row per preset and leg (generation 0, evolved) on stdout:
//   cpu_s_per_simulation   the generation's CPU over the bodies it simulated
//   generations_per_hour_cpu_p50_2cores   the paper's population (50: 51 simulations a
//                          generation) at that cost, on 2 otherwise idle cores
//
//   bench_evolved [--dir DIR] [--assets DIR] [--threads N] [--commit SHA]
//                 [--legs both|gen0|evolved] [PRESET...]
// Defaults: tests/bench/evolved, one thread, both legs, paper-exp1 paper-exp2 paper-exp3 (run
// from the repository root). Each leg is deterministic (the checkpoint holds the RNG state), so
// two builds simulate the same bodies as long as breeding is unchanged between them.
#include <time.h>
#include <unistd.h>

#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <iostream>
#include <sstream>
#include <string>
#include <vector>

#include "evo/experiment/experiment_io.hpp"
#include "evo/run/checkpoint.hpp"
#include "evo/run/evolution_run.hpp"
#include "tests/bench/bench_machine.hpp"

using namespace bhm::evo;
namespace fs = std::filesystem;

namespace {

double process_cpu_s() {
    timespec t{};
    clock_gettime(CLOCK_PROCESS_CPUTIME_ID, &t);
    return static_cast<double>(t.tv_sec) + 1e-9 * static_cast<double>(t.tv_nsec);
}

struct Leg {
    int generation = 0, population = 0, simulations = 0, ended_early = 0;
    double mean_simulated_s = 0.0, cpu_s = 0.0, wall_s = 0.0, mean_voxels = 0.0;
};

double mean_voxels(const RunState& state) {
    double sum = 0.0;
    for (const Individual& m : state.population)
        sum += m.phenotype.voxels;
    return state.population.empty() ? 0.0 : sum / static_cast<double>(state.population.size());
}

Leg run_one(EvolutionRun& run) {
    Leg leg;
    const auto t0 = std::chrono::steady_clock::now();
    const double cpu0 = process_cpu_s();
    run.run();
    leg.cpu_s = process_cpu_s() - cpu0;
    leg.wall_s = bhm::bench::seconds_since(t0);
    const RunState& s = run.state();
    const HistoryRow& row = s.history.back();
    leg.generation = row.generation;
    leg.population = s.experiment.evolution.population;
    leg.simulations = row.simulations;
    leg.ended_early = row.ended_early;
    leg.mean_simulated_s = row.mean_simulated_s;
    leg.mean_voxels = mean_voxels(s);
    return leg;
}

int run(int argc, char** argv) {
    const char* env_commit = std::getenv("BHM_COMMIT");
    std::string commit = env_commit ? env_commit : "unknown";
    std::string dir = "tests/bench/evolved", legs = "both";
    int threads = 1;
    std::vector<std::string> presets;
    for (int i = 1; i < argc; ++i) {
        const std::string a = argv[i];
        auto value = [&]() -> std::string {
            if (i + 1 >= argc) throw std::runtime_error(a + " needs a value");
            return argv[++i];
        };
        if (a == "--dir")
            dir = value();
        else if (a == "--threads")
            threads = std::stoi(value());
        else if (a == "--commit")
            commit = value();
        else if (a == "--legs")
            legs = value();
        else if (a == "--assets")
            value();  // accepted for symmetry with the other benches; the checkpoints hold the
                      // experiment
        else if (a == "--help" || a == "-h") {
            std::cout << "usage: bench_evolved [--dir DIR] [--threads N] [--commit SHA] "
                         "[--legs both|gen0|evolved] [PRESET...]\n";
            return 0;
        } else
            presets.push_back(a);
    }
    if (presets.empty()) presets = {"paper-exp1", "paper-exp2", "paper-exp3"};
    const fs::path scratch =
        fs::temp_directory_path() / ("bench_evolved-" + std::to_string(::getpid()));
    std::cout << "preset,leg,generation,population,simulations,mean_population_voxels,"
                 "ended_early,mean_simulated_s,cpu_s,wall_s,cpu_s_per_simulation,"
                 "generations_per_hour_cpu_p50_2cores,threads,machine,commit"
              << std::endl;
    const std::string machine = bhm::bench::machine_description();
    auto report = [&](const std::string& preset, const char* name, const Leg& leg) {
        const double per_sim = leg.simulations > 0 ? leg.cpu_s / leg.simulations : 0.0;
        const double gph = per_sim > 0.0 ? 3600.0 / (51.0 * per_sim / 2.0) : 0.0;
        char row[512];
        std::snprintf(row, sizeof row, "%s,%s,%d,%d,%d,%.1f,%d,%.3f,%.2f,%.2f,%.3f,%.1f,%d,%s,%s",
                      preset.c_str(), name, leg.generation, leg.population, leg.simulations,
                      leg.mean_voxels, leg.ended_early, leg.mean_simulated_s, leg.cpu_s, leg.wall_s,
                      per_sim, gph, threads, machine.c_str(), commit.c_str());
        std::cout << row << std::endl;
    };
    for (const std::string& preset : presets) {
        const fs::path checkpoint = fs::path(dir) / (preset + ".checkpoint.json");
        fs::remove_all(scratch);
        fs::create_directories(scratch / "evolved");
        fs::copy_file(checkpoint, scratch / "evolved" / "checkpoint.json");
        const LoadedCheckpoint loaded = load_checkpoint((scratch / "evolved").string());
        if (legs != "evolved") {
            RunOptions o;
            o.out_dir = (scratch / "gen0").string();
            o.generations = 1;
            o.threads = threads;
            o.seed = loaded.state.seed;
            EvolutionRun fresh(loaded.state.experiment, o);
            report(preset, "gen0", run_one(fresh));
        }
        if (legs != "gen0") {
            RunOptions o;
            o.out_dir = (scratch / "evolved").string();
            o.generations = loaded.state.generation + 2;  // one more, generation 0 counted
            o.threads = threads;
            auto resumed = EvolutionRun::resume(o);
            report(preset, "evolved", run_one(*resumed));
        }
    }
    fs::remove_all(scratch);
    return 0;
}

}  // namespace

int main(int argc, char** argv) {
    return bhm::bench::run_guarded("bench_evolved", run, argc, argv);
}
