// bench_loop_verify: what CalculiX in the evolution loop costs (issue 40: at most 15 % of the
// generation time on paper-exp1-attached with checks every 5 generations, top 3). Two runs of the
// same experiment and seed, one with evolution.verify (policy flag, so both runs breed and select
// exactly alike and make the same simulations) and one without, one after the other. Not
// interleaved a generation at a time: the checks run beside every_generations generations on a
// thread of their own (they land that many generations after their pick), so they would slow the
// other run's generations too. Run it on a quiet machine. The figure is the extra wall time of the
// run with checks over one period in steady state (generations every .. 2 every - 1: one batch
// picked after generation every - 1, running beside them and landing in the last), and over the
// whole run.
//
//   bench_loop_verify [--experiment PATH] [--generations N] [--every N] [--top K]
//                     [--threads T] [--population P] [--commit SHA]
//
// Defaults: assets/experiments/paper-exp1-attached.json (run from the repository root, as
// scripts/bench.sh does), 10 generations (checks picked after generation 4, landing in 9),
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
#include <vector>

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
        const int generations = static_cast<int>(arg_number(argc, argv, "--generations", 10));
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

        const int every = checked.evolution.verify.every_generations;
        auto run_all = [&](EvolutionRun& run, const char* label) {
            std::vector<double> times;
            for (int g = 0; g < generations; ++g) {
                const auto start = std::chrono::steady_clock::now();
                if (!run.run_generation()) throw std::runtime_error("a generation was abandoned");
                times.push_back(seconds_since(start));
                std::fprintf(stderr, "%s generation %d: %.1f s\n", label, g, times.back());
            }
            return times;
        };
        const std::vector<double> plain_t = run_all(plain, "without checks");
        const std::vector<double> checked_t = run_all(with_checks, "with checks");
        double plain_s = 0.0, checked_s = 0.0, plain_window = 0.0, checked_window = 0.0;
        for (int g = 0; g < generations; ++g) {
            plain_s += plain_t[g];
            checked_s += checked_t[g];
            if (g >= every && g < 2 * every) {
                plain_window += plain_t[g];
                checked_window += checked_t[g];
            }
            std::fprintf(stderr, "generation %d: %.1f s without checks, %.1f s with (%+.1f %%)\n",
                         g, plain_t[g], checked_t[g], 100.0 * (checked_t[g] / plain_t[g] - 1.0));
        }
        if (plain.state().history.back().best_fitness !=
            with_checks.state().history.back().best_fitness)
            throw std::runtime_error("the runs differ: the flag policy must change nothing");
        const double overhead = checked_s / plain_s - 1.0;
        const double window_overhead =
            plain_window > 0.0 ? checked_window / plain_window - 1.0 : 0.0;
        std::fprintf(stderr,
                     "%s: %d generations, %d checks (%.1f s of check wall time): %.1f s without, "
                     "%.1f s with checks: overhead %+.1f %% over the run, %+.1f %% over "
                     "generations %d-%d (one period in steady state)\n",
                     e.name.c_str(), generations, checker->checks(), checker->wall_s(), plain_s,
                     checked_s, 100.0 * overhead, 100.0 * window_overhead, every,
                     2 * every - 1);
        std::printf("machine,commit,experiment,population,generations,every,top,threads,checks,"
                    "check_wall_s,plain_s,checked_s,overhead,window_overhead\n");
        std::printf("%s,%s,%s,%d,%d,%d,%d,%d,%d,%.2f,%.2f,%.2f,%.4f,%.4f\n",
                    machine_description().c_str(),
                    arg_text(argc, argv, "--commit", "unknown").c_str(), e.name.c_str(),
                    e.evolution.population, generations,
                    checked.evolution.verify.every_generations, checked.evolution.verify.top_k,
                    threads, checker->checks(), checker->wall_s(), plain_s, checked_s, overhead,
                    window_overhead);
        return 0;
    } catch (const std::exception& error) {
        std::fprintf(stderr, "bench_loop_verify: %s\n", error.what());
        return 1;
    }
}
