// bench_algorithms: which evolutionary method finds the best bender for a fixed simulation budget
// (issue 13). For each algorithm and seed, one run of a quick-demo-sized problem until it has made
// --sims simulations; the figure is the best fitness (bend angle, degrees, for quick-demo) among
// the first --sims simulated results, in the order the run made them (cache hits and clones cost
// no simulation and count for nothing). The run is deterministic, so the figures depend on the
// seed and the code, never on the machine or its load; only wall_s does.
//
//   bench_algorithms [--sims N] [--seeds S] [--first-seed K] [--threads T] [--experiment PATH]
//                    [--settle-s S] [--evaluate-s S] [--algorithms afpo,crossover,neat,novelty]
//                    [--commit SHA]
//
// Defaults: 60 simulations, seeds 1..5, 2 threads, assets/experiments/quick-demo.json (run from
// the repository root, as scripts/bench.sh does) with its evaluation shortened to 0.1 s of settling
// + 0.5 s (one 2 Hz cycle; 0 keeps the file's) so that the 20 runs take ~10 minutes on two loaded
// cores; the four algorithms:
//   afpo       the paper's AFPO (mutation only)
//   crossover  AFPO with evolution.crossover_rate 0.3
//   neat       evolution.algorithm "neat" with its defaults
//   novelty    evolution.algorithm "novelty" with evolution.novelty.with_fitness (novelty and
//              fitness both AFPO objectives)
// An algorithm this build refuses (not built) is reported on stderr and skipped.
// CSV on stdout (one row per algorithm and seed); the summary table (mean, standard deviation,
// min, max, per seed) on stderr in Markdown, as docs/benchmarks.md shows it.
#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <iostream>
#include <memory>
#include <mutex>
#include <sstream>
#include <string>
#include <vector>

#include "evo/experiment/experiment_io.hpp"
#include "evo/experiment/body_spec_of.hpp"
#include "evo/run/evolution_run.hpp"
#include "tests/bench/bench_machine.hpp"

using namespace bhm::evo;

namespace {

using bhm::bench::machine_description;
using bhm::bench::seconds_since;

//! Runs every batch on a ThreadEvaluator and keeps each simulated fitness in batch order.
class RecordingEvaluator final : public Evaluator {
  public:
    explicit RecordingEvaluator(int threads) : inner_(threads) {}
    void evaluate(const EvaluationBatch& batch, std::vector<FitnessReport>& results) override {
        inner_.evaluate(batch, results);
        for (const auto& r : results)
            fitness_.push_back(r.fitness);
    }
    int concurrency() const override { return inner_.concurrency(); }
    const std::vector<double>& fitness() const { return fitness_; }

  private:
    ThreadEvaluator inner_;
    std::vector<double> fitness_;
};

struct Variant {
    std::string name;
    std::string description;
    bool (*apply)(Experiment&);  //!< false: this build cannot run it
};

bool set_algorithm(Experiment& e, const char* name) {
    for (std::size_t k = 0; k < kAlgorithmNames.size(); ++k)
        if (std::string(kAlgorithmNames[k]) == name) {
            e.evolution.algorithm = static_cast<Algorithm>(k);
            return validate_experiment(e, "bench").empty();
        }
    return false;
}

const std::vector<Variant> kVariants = {
    {"afpo", "AFPO, mutation only (the paper's)",
     [](Experiment& e) { return set_algorithm(e, "afpo"); }},
    {"crossover", "AFPO + crossover_rate 0.3",
     [](Experiment& e) {
         e.evolution.crossover_rate = 0.3;
         return set_algorithm(e, "afpo");
     }},
    {"neat", "NEAT (defaults)", [](Experiment& e) { return set_algorithm(e, "neat"); }},
    {"novelty", "novelty search + fitness objective",
     [](Experiment& e) {
         e.evolution.novelty.with_fitness = true;
         return set_algorithm(e, "novelty");
     }},
};

struct Outcome {
    std::string algorithm;
    std::uint64_t seed = 0;
    int simulations = 0;  //!< made by the run (the last generation may pass the budget)
    int generations = 0;
    double best = 0.0;  //!< best fitness among the first `budget` simulations
    double wall_s = 0.0;
};

double mean(const std::vector<double>& v) {
    double s = 0.0;
    for (double x : v)
        s += x;
    return v.empty() ? 0.0 : s / static_cast<double>(v.size());
}

double standard_deviation(const std::vector<double>& v) {
    if (v.size() < 2) return 0.0;
    const double m = mean(v);
    double s = 0.0;
    for (double x : v)
        s += (x - m) * (x - m);
    return std::sqrt(s / static_cast<double>(v.size() - 1));
}

}  // namespace

int run(int argc, char** argv) {
    const char* env_commit = std::getenv("BHM_COMMIT");
    std::string commit = env_commit ? env_commit : "unknown";
    std::string experiment_path = "assets/experiments/quick-demo.json";
    int budget = 60, seeds = 5, threads = 2;
    double settle_s = 0.1, evaluate_s = 0.5;
    std::uint64_t first_seed = 1;
    std::vector<std::string> wanted = {"afpo", "crossover", "neat", "novelty"};
    for (int i = 1; i < argc; ++i) {
        const std::string a = argv[i];
        auto value = [&]() -> std::string {
            if (i + 1 >= argc) throw std::runtime_error(a + " needs a value");
            return argv[++i];
        };
        if (a == "--commit")
            commit = value();
        else if (a == "--sims")
            budget = std::stoi(value());
        else if (a == "--seeds")
            seeds = std::stoi(value());
        else if (a == "--first-seed")
            first_seed = std::stoull(value());
        else if (a == "--threads")
            threads = std::stoi(value());
        else if (a == "--experiment")
            experiment_path = value();
        else if (a == "--settle-s")
            settle_s = std::stod(value());
        else if (a == "--evaluate-s")
            evaluate_s = std::stod(value());
        else if (a == "--algorithms") {
            wanted.clear();
            std::stringstream list(value());
            std::string item;
            while (std::getline(list, item, ','))
                wanted.push_back(item);
        } else
            throw std::runtime_error("unknown argument " + a);
    }
    if (budget < 1 || seeds < 1 || threads < 1)
        throw std::runtime_error("--sims, --seeds and --threads must be >= 1");
    Experiment base = load_experiment(experiment_path);
    if (settle_s > 0.0) base.simulation.settle_s = settle_s;
    if (evaluate_s > 0.0) base.simulation.evaluate_s = evaluate_s;
    if (const auto problems = validate_experiment(base, experiment_path); !problems.empty())
        throw std::runtime_error(problems.front().to_string());

    std::cout << "algorithm,seed,simulation_budget,simulations,generations,best_fitness,measure,"
                 "experiment,evaluation_s,threads,wall_s,machine,commit"
              << std::endl;
    const std::string machine = machine_description();
    const char* measure = kFitnessNames[static_cast<std::size_t>(base.fitness.measure)];
    std::vector<Outcome> outcomes;
    std::vector<std::string> run_names;
    for (const auto& name : wanted) {
        const auto variant = std::find_if(kVariants.begin(), kVariants.end(),
                                          [&](const Variant& v) { return v.name == name; });
        if (variant == kVariants.end()) throw std::runtime_error("unknown algorithm " + name);
        Experiment e = base;
        if (!variant->apply(e)) {
            std::cerr << "bench_algorithms: " << name << " is not built in this bhm; skipped\n";
            continue;
        }
        run_names.push_back(name);
        for (int s = 0; s < seeds; ++s) {
            Outcome o;
            o.algorithm = name;
            o.seed = first_seed + static_cast<std::uint64_t>(s);
            RunOptions options;  // no out_dir: everything in memory
            options.seed = o.seed;
            options.threads = threads;
            options.generations = 1'000'000;  // the simulation budget stops it
            options.wall_budget_h = 1e4;
            auto evaluator = std::make_shared<RecordingEvaluator>(threads);
            options.evaluator = evaluator;
            const auto start = std::chrono::steady_clock::now();
            EvolutionRun run(e, options);
            while (static_cast<int>(evaluator->fitness().size()) < budget) {
                if (!run.run_generation()) throw std::runtime_error("generation abandoned");
                ++o.generations;
            }
            o.wall_s = seconds_since(start);
            const auto& f = evaluator->fitness();
            o.simulations = static_cast<int>(f.size());
            o.best = *std::max_element(f.begin(), f.begin() + budget);
            outcomes.push_back(o);
            char row[512];
            std::snprintf(row, sizeof row, "%s,%llu,%d,%d,%d,%.6g,%s,%s,%.3g,%d,%.2f,%s,%s",
                          name.c_str(), static_cast<unsigned long long>(o.seed), budget,
                          o.simulations, o.generations, o.best, measure, base.name.c_str(),
                          evaluation_seconds(base), threads, o.wall_s, machine.c_str(),
                          commit.c_str());
            std::cout << row << std::endl;
            std::cerr << name << " seed " << o.seed << ": best " << o.best << " after " << budget
                      << " simulations (" << o.generations << " generations, " << o.wall_s
                      << " s)\n";
        }
    }

    // docs/benchmarks.md's table.
    std::cerr << "\n| algorithm | mean | sd | min | max | per seed (" << first_seed << ".."
              << first_seed + static_cast<std::uint64_t>(seeds) - 1
              << ") |\n|---|---|---|---|---|---|\n";
    for (const auto& name : run_names) {
        std::vector<double> best;
        std::string per_seed;
        for (const auto& o : outcomes)
            if (o.algorithm == name) {
                best.push_back(o.best);
                char v[32];
                std::snprintf(v, sizeof v, "%s%.1f", per_seed.empty() ? "" : ", ", o.best);
                per_seed += v;
            }
        const auto variant = std::find_if(kVariants.begin(), kVariants.end(),
                                          [&](const Variant& v) { return v.name == name; });
        char line[512];
        std::snprintf(line, sizeof line, "| %s | %.1f | %.1f | %.1f | %.1f | %s |\n",
                      variant->description.c_str(), mean(best), standard_deviation(best),
                      *std::min_element(best.begin(), best.end()),
                      *std::max_element(best.begin(), best.end()), per_seed.c_str());
        std::cerr << line;
    }
    return 0;
}

int main(int argc, char** argv) {
    try {
        return run(argc, argv);
    } catch (const std::exception& e) {
        std::cerr << "bench_algorithms: " << e.what() << "\n";
        return 1;
    }
}
