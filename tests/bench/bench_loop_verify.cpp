// bench_loop_verify: what CalculiX in the evolution loop costs (issue 40: at most 15 % of the
// generation time on paper-exp1-attached with checks every 5 generations, top 3). Two runs of the
// same experiment and seed, one with evolution.verify (policy flag, so both runs breed and select
// exactly alike and make the same simulations) and one without, advanced one generation at a time
// in turn, so that the machine's load falls on both alike; the figure is the extra wall time of
// the run with checks over the whole window, against the run without.
//
//   bench_loop_verify [--experiment PATH] [--generations N] [--every N] [--top K]
//                     [--threads T] [--population P] [--commit SHA]
//
// Defaults: assets/experiments/paper-exp1-attached.json (run from the repository root, as
// scripts/bench.sh does), 11 generations (checks after generations 4 and 9, landing in 5 and 10),
// every 5, top 3, 2 threads, the experiment's population. CSV on stdout (one row), each
// generation's pair of wall times on stderr.
#include <chrono>
#include <cstdio>
#include <cstdlib>
#include <ctime>
#include <iostream>
#include <memory>
#include <mutex>
#include <string>

#include "evo/experiment/experiment_io.hpp"
#include "evo/run/evolution_run.hpp"
#include "evo/verify/continuum_checker.hpp"
#include "tests/bench/bench_machine.hpp"

using namespace bhm::evo;

namespace {

using bhm::bench::machine_description;
using bhm::bench::seconds_since;

//! The CalculiX checker, timed: wall time of each check on the job's thread.
class TimedChecker final : public ContinuumChecker {
  public:
    std::optional<LoopCheck> check(const Experiment& rules, const LoopCheckRequest& body,
                                   const std::string& out_dir,
                                   const std::atomic<bool>& cancel) override {
        const auto start = std::chrono::steady_clock::now();
        auto result = inner_.check(rules, body, out_dir, cancel);
        std::lock_guard lock(mutex_);
        wall_s_ += seconds_since(start);
        ++checks_;
        if (result)
            std::fprintf(stderr, "  check of individual %lld: %s (%.1f s)\n",
                         static_cast<long long>(body.id), result->verdict.c_str(),
                         seconds_since(start));
        return result;
    }
    std::string unavailable() const override { return inner_.unavailable(); }
    double wall_s() const { return wall_s_; }
    int checks() const { return checks_; }

  private:
    CalculixChecker inner_;
    std::mutex mutex_;
    double wall_s_ = 0.0;
    int checks_ = 0;
};

double arg_number(int argc, char** argv, const std::string& name, double fallback) {
    for (int i = 1; i + 1 < argc; ++i)
        if (argv[i] == name) return std::atof(argv[i + 1]);
    return fallback;
}

std::string arg_text(int argc, char** argv, const std::string& name, const std::string& fallback) {
    for (int i = 1; i + 1 < argc; ++i)
        if (argv[i] == name) return argv[i + 1];
    return fallback;
}

}  // namespace

int main(int argc, char** argv) {
    for (int i = 1; i < argc; ++i)
        if (std::string(argv[i]) == "--help") {
            std::puts("usage: bench_loop_verify [--experiment PATH] [--generations N] [--every N] "
                      "[--top K] [--threads T] [--population P] [--commit SHA]");
            return 0;
        }
    try {
        Experiment e = load_experiment(
            arg_text(argc, argv, "--experiment", "assets/experiments/paper-exp1-attached.json"));
        const int generations = static_cast<int>(arg_number(argc, argv, "--generations", 11));
        const int threads = static_cast<int>(arg_number(argc, argv, "--threads", 2));
        e.evolution.population =
            static_cast<int>(arg_number(argc, argv, "--population", e.evolution.population));
        Experiment checked = e;
        checked.evolution.verify.every_generations =
            static_cast<int>(arg_number(argc, argv, "--every", 5));
        checked.evolution.verify.top_k = static_cast<int>(arg_number(argc, argv, "--top", 3));
        checked.evolution.verify.policy = VerifyPolicy::Flag;

        const std::string stamp = std::to_string(std::time(nullptr));
        RunOptions plain_options;
        plain_options.generations = generations;
        plain_options.threads = threads;
        RunOptions checked_options = plain_options;
        // Kept on disk, as a real run keeps them (RUN/verify/): writing them is part of the cost.
        checked_options.out_dir = "/tmp/bench-loop-verify-" + stamp;
        auto checker = std::make_shared<TimedChecker>();
        checked_options.checker = checker;
        plain_options.out_dir = "/tmp/bench-loop-verify-plain-" + stamp;
        EvolutionRun plain(e, plain_options);
        EvolutionRun with_checks(checked, checked_options);

        double plain_s = 0.0, checked_s = 0.0;
        for (int g = 0; g < generations; ++g) {
            // Alternate which run goes first, so neither always follows the other's cache state.
            double t_plain = 0.0, t_checked = 0.0;
            for (int k = 0; k < 2; ++k) {
                const bool plain_turn = (k == 0) == (g % 2 == 0);
                const auto start = std::chrono::steady_clock::now();
                if (!(plain_turn ? plain : with_checks).run_generation())
                    throw std::runtime_error("a generation was abandoned");
                (plain_turn ? t_plain : t_checked) = seconds_since(start);
            }
            plain_s += t_plain;
            checked_s += t_checked;
            std::fprintf(stderr, "generation %d: %.1f s without checks, %.1f s with (%+.1f %%)\n",
                         g, t_plain, t_checked, 100.0 * (t_checked / t_plain - 1.0));
        }
        if (plain.state().history.back().best_fitness !=
            with_checks.state().history.back().best_fitness)
            throw std::runtime_error("the runs differ: the flag policy must change nothing");
        const double overhead = checked_s / plain_s - 1.0;
        std::fprintf(stderr,
                     "%s: %d generations, %d checks (%.1f s of check wall time): %.1f s without, "
                     "%.1f s with checks: overhead %+.1f %% of the generation time\n",
                     e.name.c_str(), generations, checker->checks(), checker->wall_s(), plain_s,
                     checked_s, 100.0 * overhead);
        std::printf("machine,commit,experiment,population,generations,every,top,threads,checks,"
                    "check_wall_s,plain_s,checked_s,overhead\n");
        std::printf("%s,%s,%s,%d,%d,%d,%d,%d,%d,%.2f,%.2f,%.2f,%.4f\n",
                    machine_description().c_str(),
                    arg_text(argc, argv, "--commit", "unknown").c_str(), e.name.c_str(),
                    e.evolution.population, generations,
                    checked.evolution.verify.every_generations, checked.evolution.verify.top_k,
                    threads, checker->checks(), checker->wall_s(), plain_s, checked_s, overhead);
        return 0;
    } catch (const std::exception& error) {
        std::fprintf(stderr, "bench_loop_verify: %s\n", error.what());
        return 1;
    }
}
