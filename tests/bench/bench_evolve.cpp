// bench_evolve: evolution throughput on the paper presets, as CSV (one row per preset and thread
// count). Full 11 s evaluations of the paper's bodies take minutes each, so each simulation here
// covers the first --sim-seconds of the evaluation and the rate is scaled to full length (the
// engine's cost is linear in simulated time: a fixed step). The coordinator's share of a
// generation (P mutants with neutral retries, one newcomer, decoding) is timed for real.
// generations_per_hour uses wall time; generations_per_hour_cpu projects the measured CPU time
// per simulation onto `threads` idle cores (what a shared machine cannot show by wall time).
//
//   bench_evolve [--sims N (0: all)] [--sim-seconds S] [--threads-list 1,2] [--assets DIR]
//                [--commit SHA] [--poisson-off] [--no-periodic-end] [PRESET...]
// --poisson-off sets every material's Poisson ratio to 0 (the engine's Poisson coupling off), to
// show that coupling's share of the cost. Evaluations end when the motion repeats
// (simulation.end_when_periodic, on in the presets) only when --sim-seconds is the full evaluation
// (an early end of a shortened one would break the linear scaling); --no-periodic-end switches it
// off there too, to show its share. ended_early and mean_simulated_s say how far they ran.
//
// Defaults: one simulation of 0.2 s for each body of a whole random generation 0 (the preset's
// population; a body's cost follows its voxels, and the first few random bodies are no sample of
// a generation: in paper-exp1 the first 4 average 88 voxels, all 50 330), presets paper-exp1,
// paper-exp2 and paper-exp3 from assets/experiments (run from the repository root, as
// scripts/bench.sh does), threads 1 and 2. CSV on stdout, notes on stderr; the commit comes from
// --commit or $BHM_COMMIT.
#include <sys/utsname.h>
#include <time.h>

#include <algorithm>
#include <chrono>
#include <cstdio>
#include <cstdlib>
#include <fstream>
#include <iostream>
#include <sstream>
#include <string>
#include <thread>
#include <vector>

#include "evo/evaluate/constraints.hpp"
#include "evo/evaluate/fitness.hpp"
#include "evo/evaluate/worker_pool.hpp"
#include "evo/experiment/experiment_io.hpp"
#include "evo/experiment/body_spec_of.hpp"
#include "evo/genome/phenotype.hpp"
#include "evo/search/mutation.hpp"
#include "tests/bench/bench_machine.hpp"

using namespace bhm::evo;

namespace {

using bhm::bench::machine_description;
using bhm::bench::seconds_since;

//! CPU seconds of every thread of this process.
double process_cpu_s() {
    timespec t{};
    clock_gettime(CLOCK_PROCESS_CPUTIME_ID, &t);
    return static_cast<double>(t.tv_sec) + 1e-9 * static_cast<double>(t.tv_nsec);
}

struct Population {
    std::vector<Genome> genomes;
    std::vector<Phenotype> phenotypes;
};

//! P random valid individuals, as generation 0 draws them.
Population random_population(const Experiment& e, const Developer& dev, int count, Rng& rng) {
    Population p;
    while (static_cast<int>(p.genomes.size()) < count) {
        Genome g = random_genome(e.evolution.cppn, rng);
        Phenotype ph = dev.develop(g);
        if (!constraint_violation(e.fitness.constraints, e.boundary, dev.space(), ph).empty())
            continue;
        p.genomes.push_back(std::move(g));
        p.phenotypes.push_back(std::move(ph));
    }
    return p;
}

}  // namespace

int run(int argc, char** argv) {
    const char* env_commit = std::getenv("BHM_COMMIT");
    std::string commit = env_commit ? env_commit : "unknown";
    std::string assets = "assets/experiments";
    int sims = 0;  // 0: the whole population
    double sim_seconds = 0.2;
    std::vector<int> thread_counts = {1, 2};
    std::vector<std::string> presets;
    bool poisson_off = false, periodic_end = true;
    for (int i = 1; i < argc; ++i) {
        const std::string a = argv[i];
        auto value = [&]() -> std::string {
            if (i + 1 >= argc) throw std::runtime_error(a + " needs a value");
            return argv[++i];
        };
        if (a == "--commit")
            commit = value();
        else if (a == "--assets")
            assets = value();
        else if (a == "--sims") {
            sims = std::stoi(value());
            if (sims < 0) throw std::runtime_error("--sims needs a count >= 0 (0: the population)");
        } else if (a == "--sim-seconds")
            sim_seconds = std::stod(value());
        else if (a == "--poisson-off")
            poisson_off = true;
        else if (a == "--no-periodic-end")
            periodic_end = false;
        else if (a == "--threads-list") {
            thread_counts.clear();
            std::stringstream list(value());
            std::string item;
            while (std::getline(list, item, ','))
                thread_counts.push_back(std::stoi(item));
        } else
            presets.push_back(a);
    }
    if (presets.empty()) presets = {"paper-exp1", "paper-exp2", "paper-exp3"};

    std::cout
        << "preset,threads,population,simulations,mean_voxels,simulated_s_each,full_evaluation_s,"
           "wall_s,sim_s_per_wall_s,simulations_per_s_full,coordinator_s_per_generation,"
           "generations_per_hour,cpu_s_per_full_simulation,generations_per_hour_cpu,"
           "ended_early,mean_simulated_s,hardware_threads,machine,commit"
        << std::endl;
    const std::string machine = machine_description();
    for (const auto& preset : presets) {
        const std::string path = assets + "/" + preset + ".json";
        Experiment full = load_experiment(path);
        if (poisson_off)
            for (MaterialEntry& m : full.materials)
                m.physics.poisson_ratio = 0.0;
        const Developer dev(full);
        const int P = full.evolution.population;
        Rng rng(full.evolution.seed);

        // Coordinator work of one generation, measured: P mutants (with neutral retries) +
        // newcomer.
        Population population = random_population(full, dev, P, rng);
        const int preset_sims = sims > 0 ? sims : P;
        const auto t_coord = std::chrono::steady_clock::now();
        const double cpu_coord = process_cpu_s();
        for (int k = 0; k < P; ++k)
            mutate_until_new(population.genomes[static_cast<std::size_t>(k)],
                             population.phenotypes[static_cast<std::size_t>(k)], dev,
                             full.fitness.constraints, full.evolution.cppn,
                             full.evolution.max_neutral_retries, rng);
        random_population(full, dev, 1, rng);
        const double coordinator_s = seconds_since(t_coord);
        const double coordinator_cpu_s = process_cpu_s() - cpu_coord;

        // Simulations: the first sim_seconds of evaluations of the first `preset_sims` random
        // bodies.
        Experiment shortened = full;
        const double full_s = evaluation_seconds(full);
        shortened.simulation.settle_s = std::min(full.simulation.settle_s, sim_seconds / 2);
        shortened.simulation.evaluate_s = sim_seconds - shortened.simulation.settle_s;
        if (!periodic_end || sim_seconds < full_s - 1e-9)
            shortened.simulation.end_when_periodic = false;
        double voxels = 0;
        for (int k = 0; k < preset_sims; ++k)
            voxels += population.phenotypes[static_cast<std::size_t>(k % P)].voxels;
        voxels /= preset_sims;
        for (int threads : thread_counts) {
            std::vector<FitnessReport> reports(static_cast<std::size_t>(preset_sims));
            const auto t_sim = std::chrono::steady_clock::now();
            const double cpu_sim = process_cpu_s();
            parallel_for(preset_sims, threads, [&](int k) {
                reports[static_cast<std::size_t>(k)] = evaluate_body(
                    shortened, population.phenotypes[static_cast<std::size_t>(k % P)].body);
            });
            const double wall_s = seconds_since(t_sim);
            int ended_early = 0;
            double simulated_s = 0.0;
            for (const auto& r : reports) {
                ended_early += r.ended_early ? 1 : 0;
                simulated_s += r.simulated_s / preset_sims;
            }
            // CPU time of the simulations, scaled to full length: on a machine shared with other
            // jobs the wall-clock rate says more about the load than about the code, so the
            // _cpu figure projects a generation onto `threads` otherwise idle cores.
            const double cpu_per_full_sim =
                (process_cpu_s() - cpu_sim) / preset_sims * full_s / sim_seconds;
            const double generation_cpu_s =
                coordinator_cpu_s + (P + 1) * cpu_per_full_sim / threads;
            const double sim_rate =
                preset_sims * sim_seconds / wall_s;      // simulated seconds per wall second
            const double full_rate = sim_rate / full_s;  // full evaluations per second
            // A generation simulates at most P + 1 new bodies (fewer with cache hits and clones).
            const double generation_s = coordinator_s + (P + 1) / full_rate;
            char row[640];
            std::snprintf(
                row, sizeof row,
                "%s,%d,%d,%d,%.1f,%.3f,%.3f,%.3f,%.4f,%.6f,%.3f,%.3f,%.3f,%.3f,%d,%.3f,%u,"
                "%s,%s",
                preset.c_str(), threads, P, preset_sims, voxels, sim_seconds, full_s, wall_s,
                sim_rate, full_rate, coordinator_s, 3600.0 / generation_s, cpu_per_full_sim,
                3600.0 / generation_cpu_s, ended_early, simulated_s,
                std::thread::hardware_concurrency(), machine.c_str(), commit.c_str());
            std::cout << row << std::endl;
            std::cerr << preset << ", " << threads << " thread(s): " << full_rate
                      << " full simulations/s, " << 3600.0 / generation_s << " generations/hour; "
                      << cpu_per_full_sim << " CPU s per full simulation, "
                      << 3600.0 / generation_cpu_s << " generations/hour on idle cores\n";
        }
    }
    return 0;
}

int main(int argc, char** argv) {
    try {
        return run(argc, argv);
    } catch (const std::exception& e) {
        std::cerr << "bench_evolve: " << e.what() << "\n";
        return 1;
    }
}
