// bench_controllers: NEAT, HyperNEAT and the plain GA evolving CONTROLLERS for two fixed corpus
// morphologies, one high- and one low-performing (issue 44; the published finding, arXiv
// 2408.09107 / 2411.08261, is NEAT >= HyperNEAT > GA). For each body, algorithm and seed, one
// evolution.controller "fixed_body" run until it has made --sims simulations; the figure is the
// best fitness (paper-exp1: the centre of mass's displacement) among those first --sims
// simulations, in the order the run made them (cache hits and clones cost none). Per body and
// algorithm: mean, standard deviation, the 95 % t interval of the mean; per body: Kruskal-Wallis
// over the three algorithms and the pairwise two-sided Mann-Whitney U tests
// (tests/bench/rank_stats.hpp: exact without ties). Deterministic: the figures depend on the seeds
// and the code, never on the machine; only wall_s does.
//
//   bench_controllers [--sims N] [--seeds S] [--first-seed K] [--population P] [--threads T]
//                     [--settle-s S] [--evaluate-s S] [--min-active N] [--max-voxels N]
//                     [--algorithms a,b,...]
//                     [--experiment PATH] [--corpus FILE,...] [--commit SHA]
//
// The bodies: the bodies of the --corpus files (default tests/bench/corpus/paper-exp1-attached.json
// and paper-exp1-attached-champions.json: 50 random generation-0 bodies and 2 short-run champions,
// all attached to the fixed face, so that what moves them is their actuation) with at least
// --min-active active voxels (default 20: a controller needs voxels to drive) and at most
// --max-voxels voxels (default 100: the simulations' cost) are simulated once under the
// experiment's own uniform actuation (the screen); the "high" body is the one that moves
// furthest, the "low" one the one that moves least. Defaults: 30 simulations, population 8, seeds
// 1..5, 2 threads, assets/experiments/paper-exp1-attached.json with its evaluation shortened to
// 0.25 s settle + 1 s (two 2 Hz cycles). CSV on stdout (one row per body, algorithm and seed);
// the screen and the Markdown tables on stderr.
#include <algorithm>
#include <chrono>
#include <cstdio>
#include <cstdlib>
#include <fstream>
#include <iostream>
#include <memory>
#include <sstream>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "evo/experiment/body_spec_of.hpp"
#include "evo/experiment/experiment_io.hpp"
#include "evo/genome/body_ops.hpp"
#include "evo/run/evolution_run.hpp"
#include "tests/bench/bench_machine.hpp"
#include "tests/bench/rank_stats.hpp"

using namespace bhm::evo;
using namespace bhm::bench;

namespace {

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

struct CorpusBody {
    std::string label;  //!< file:index (name)
    Body body;
    int active = 0;
    double uniform_fitness = 0.0;
};

std::vector<CorpusBody> read_corpus(const std::vector<std::string>& files) {
    std::vector<CorpusBody> out;
    for (const auto& file : files) {
        std::ifstream in(file);
        if (!in) throw std::runtime_error(file + ": cannot open");
        const auto json = nlohmann::json::parse(in);
        const auto& bodies = json.at("bodies");
        for (std::size_t i = 0; i < bodies.size(); ++i) {
            CorpusBody b;
            const std::string name = bodies[i].value("name", "");
            b.label = file.substr(file.find_last_of('/') + 1) + ":" + std::to_string(i) +
                      (name.empty() ? "" : " (" + name + ")");
            b.body = parse_body(bodies[i].at("body"), file);
            out.push_back(std::move(b));
        }
    }
    return out;
}

Algorithm algorithm_named(const std::string& name) {
    for (std::size_t k = 0; k < kAlgorithmNames.size(); ++k)
        if (name == kAlgorithmNames[k]) return static_cast<Algorithm>(k);
    throw std::runtime_error("unknown algorithm " + name);
}

std::string fixed(double v, int digits = 4) {
    char s[64];
    std::snprintf(s, sizeof s, "%.*f", digits, v);
    return s;
}

std::string p_text(const RankTest& t) {
    char s[64];
    std::snprintf(s, sizeof s, "%.3g%s", t.p, t.exact ? " (exact)" : " (normal)");
    return s;
}

}  // namespace

int run(int argc, char** argv) {
    const char* env_commit = std::getenv("BHM_COMMIT");
    std::string commit = env_commit ? env_commit : "unknown";
    std::string experiment_path = "assets/experiments/paper-exp1-attached.json";
    std::vector<std::string> corpus = {"tests/bench/corpus/paper-exp1-attached.json",
                                       "tests/bench/corpus/paper-exp1-attached-champions.json"};
    int budget = 30, seeds = 5, threads = 2, population = 8, min_active = 20, max_voxels = 100;
    double settle_s = 0.25, evaluate_s = 1.0;
    std::uint64_t first_seed = 1;
    std::vector<std::string> wanted = {"neat", "hyperneat", "ga"};
    auto split = [](const std::string& text) {
        std::vector<std::string> items;
        std::stringstream list(text);
        std::string item;
        while (std::getline(list, item, ','))
            items.push_back(item);
        return items;
    };
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
        else if (a == "--population")
            population = std::stoi(value());
        else if (a == "--threads")
            threads = std::stoi(value());
        else if (a == "--min-active")
            min_active = std::stoi(value());
        else if (a == "--max-voxels")
            max_voxels = std::stoi(value());
        else if (a == "--experiment")
            experiment_path = value();
        else if (a == "--corpus")
            corpus = split(value());
        else if (a == "--settle-s")
            settle_s = std::stod(value());
        else if (a == "--evaluate-s")
            evaluate_s = std::stod(value());
        else if (a == "--algorithms")
            wanted = split(value());
        else
            throw std::runtime_error("unknown argument " + a);
    }
    if (budget < 1 || seeds < 1 || threads < 1 || population < 2)
        throw std::runtime_error("--sims, --seeds, --threads must be >= 1, --population >= 2");
    Experiment base = load_experiment(experiment_path);
    if (settle_s > 0.0) base.simulation.settle_s = settle_s;
    if (evaluate_s > 0.0) base.simulation.evaluate_s = evaluate_s;
    base.evolution.population = population;
    if (const auto problems = validate_experiment(base, experiment_path); !problems.empty())
        throw std::runtime_error(problems.front().to_string());
    const auto start_all = std::chrono::steady_clock::now();

    // The screen: every eligible corpus body once under the experiment's uniform actuation.
    std::vector<CorpusBody> bodies;
    std::vector<Body> framed;
    for (auto& b : read_corpus(corpus)) {
        Body f = apply_frame_and_overrides(base, b.body);
        b.active = count_active(f, base.materials);
        if (b.active < min_active || count_filled(f) > max_voxels) continue;
        framed.push_back(std::move(f));
        bodies.push_back(std::move(b));
    }
    if (bodies.size() < 2)
        throw std::runtime_error("fewer than two corpus bodies within --min-active, --max-voxels");
    {
        EvaluationBatch batch;
        batch.rules = &base;
        for (const auto& f : framed)
            batch.bodies.push_back(&f);
        std::vector<FitnessReport> reports;
        ThreadEvaluator(threads).evaluate(batch, reports);
        for (std::size_t i = 0; i < bodies.size(); ++i)
            bodies[i].uniform_fitness = reports[i].fitness;
    }
    std::size_t high = 0, low = 0;
    for (std::size_t i = 0; i < bodies.size(); ++i) {
        std::cerr << "  " << bodies[i].label << ": " << count_filled(framed[i]) << " voxels, "
                  << bodies[i].active << " active, uniform phase " << bodies[i].uniform_fitness
                  << "\n";
        if (bodies[i].uniform_fitness > bodies[high].uniform_fitness) high = i;
        if (bodies[i].uniform_fitness < bodies[low].uniform_fitness) low = i;
    }
    const char* measure = kFitnessNames[static_cast<std::size_t>(base.fitness.measure)];
    std::cerr << "screen (" << bodies.size() << " corpus bodies, uniform phase, " << measure
              << "): high = " << bodies[high].label << " " << bodies[high].uniform_fitness << " ("
              << bodies[high].active << " active voxels), low = " << bodies[low].label << " "
              << bodies[low].uniform_fitness << " (" << bodies[low].active << " active voxels), "
              << seconds_since(start_all) << " s\n";

    std::cout << "body,body_label,algorithm,seed,simulation_budget,simulations,generations,"
                 "best_fitness,uniform_fitness,measure,experiment,evaluation_s,population,threads,"
                 "wall_s,machine,commit"
              << std::endl;
    const std::string machine = machine_description();
    struct Cell {
        std::string body, algorithm;
        std::vector<double> best;
    };
    std::vector<Cell> cells;
    for (const auto& [role, index] : {std::pair<std::string, std::size_t>{"high", high},
                                      std::pair<std::string, std::size_t>{"low", low}}) {
        for (const auto& name : wanted) {
            Experiment e = base;
            e.evolution.algorithm = algorithm_named(name);
            e.evolution.controller.mode = ControllerMode::FixedBody;
            e.evolution.controller.body = bodies[index].body;
            if (const auto problems = validate_experiment(e, "bench"); !problems.empty())
                throw std::runtime_error(problems.front().to_string());
            Cell cell{role, name, {}};
            for (int s = 0; s < seeds; ++s) {
                const std::uint64_t seed = first_seed + static_cast<std::uint64_t>(s);
                RunOptions options;  // no out_dir: everything in memory
                options.seed = seed;
                options.threads = threads;
                options.generations = 1'000'000;  // the simulation budget stops it
                options.wall_budget_h = 1e4;
                auto evaluator = std::make_shared<RecordingEvaluator>(threads);
                options.evaluator = evaluator;
                const auto start = std::chrono::steady_clock::now();
                EvolutionRun run(e, options);
                int generations = 0;
                while (static_cast<int>(evaluator->fitness().size()) < budget) {
                    if (!run.run_generation()) throw std::runtime_error("generation abandoned");
                    ++generations;
                }
                const double wall = seconds_since(start);
                const auto& f = evaluator->fitness();
                const double best = *std::max_element(f.begin(), f.begin() + budget);
                cell.best.push_back(best);
                char row[768];
                std::snprintf(
                    row, sizeof row, "%s,%s,%s,%llu,%d,%d,%d,%.6g,%.6g,%s,%s,%.3g,%d,%d,%.2f,%s,%s",
                    role.c_str(), bodies[index].label.c_str(), name.c_str(),
                    static_cast<unsigned long long>(seed), budget, static_cast<int>(f.size()),
                    generations, best, bodies[index].uniform_fitness, measure, base.name.c_str(),
                    evaluation_seconds(base), population, threads, wall, machine.c_str(),
                    commit.c_str());
                std::cout << row << std::endl;
                std::cerr << role << " " << name << " seed " << seed << ": best " << best
                          << " after " << budget << " simulations (" << generations
                          << " generations, " << wall << " s)\n";
            }
            cells.push_back(std::move(cell));
        }
    }

    // docs/hyperneat.md's tables.
    for (const char* role : {"high", "low"}) {
        const std::size_t index = std::string(role) == "high" ? high : low;
        std::cerr
            << "\n"
            << role << " body " << bodies[index].label
            << " (uniform phase: " << bodies[index].uniform_fitness << "), best " << measure
            << " in " << budget << " simulations, seeds " << first_seed << ".."
            << first_seed + static_cast<std::uint64_t>(seeds) - 1
            << "\n\n| algorithm | mean | sd | 95 % CI (t) | per seed |\n|---|---|---|---|---|\n";
        std::vector<const Cell*> mine;
        for (const auto& c : cells)
            if (c.body == role) mine.push_back(&c);
        for (const Cell* c : mine) {
            const double m = sample_mean(c->best), h = ci95_half_width(c->best);
            std::string per_seed;
            for (double v : c->best)
                per_seed += (per_seed.empty() ? "" : ", ") + fixed(v);
            std::cerr << "| " << c->algorithm << " | " << fixed(m) << " | "
                      << fixed(sample_sd(c->best)) << " | [" << fixed(m - h) << ", " << fixed(m + h)
                      << "] | " << per_seed << " |\n";
        }
        if (mine.size() >= 2 && mine.size() <= 3) {
            std::vector<std::vector<double>> samples;
            for (const Cell* c : mine)
                samples.push_back(c->best);
            const auto kw = kruskal_wallis(samples);
            std::cerr << "\nKruskal-Wallis H = " << fixed(kw.statistic, 3)
                      << ", p = " << fixed(kw.p, 4) << " (chi-square, " << mine.size() - 1
                      << " df)\n";
            for (std::size_t a = 0; a < mine.size(); ++a)
                for (std::size_t b = a + 1; b < mine.size(); ++b) {
                    const auto mw = mann_whitney(mine[a]->best, mine[b]->best);
                    std::cerr << "Mann-Whitney " << mine[a]->algorithm << " vs "
                              << mine[b]->algorithm << ": U = " << fixed(mw.statistic, 1) << " of "
                              << mine[a]->best.size() * mine[b]->best.size()
                              << ", p = " << p_text(mw) << "\n";
                }
        }
    }
    std::cerr << "\ntotal " << seconds_since(start_all) << " s\n";
    return 0;
}

int main(int argc, char** argv) {
    try {
        return run(argc, argv);
    } catch (const std::exception& e) {
        std::cerr << "bench_controllers: " << e.what() << "\n";
        return 1;
    }
}
