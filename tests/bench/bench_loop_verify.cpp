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
//
// Wall time on a shared machine is as noisy as its load (the load average is printed at the start
// and the end), so CPU time is measured too, which other processes do not move: the checks' (ccx,
// a child process, and the check thread's own: our engine's quasi-static answer, meshing,
// comparing, files) against the evaluation's per generation (the run without checks, the process's
// CPU). With every core busy, the wall overhead is about that ratio, less what the checks fill of
// the evaluation's idle tails. Each check's solves (report.json's fem.solves) on stderr.
#include <sys/resource.h>

#include <chrono>
#include <cstdio>
#include <cstdlib>
#include <ctime>
#include <fstream>
#include <iostream>
#include <memory>
#include <mutex>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "evo/experiment/experiment_io.hpp"
#include "evo/run/evolution_run.hpp"
#include "evo/verify/continuum_checker.hpp"
#include "tests/bench/bench_machine.hpp"

using namespace bhm::evo;

namespace {

using bhm::bench::machine_description;
using bhm::bench::seconds_since;

double thread_cpu_s() {
    timespec t{};
    clock_gettime(CLOCK_THREAD_CPUTIME_ID, &t);
    return static_cast<double>(t.tv_sec) + 1e-9 * static_cast<double>(t.tv_nsec);
}

double process_cpu_s(int who) {  // RUSAGE_SELF (every thread) or RUSAGE_CHILDREN (ccx)
    rusage u{};
    getrusage(who, &u);
    return static_cast<double>(u.ru_utime.tv_sec + u.ru_stime.tv_sec) +
           1e-6 * static_cast<double>(u.ru_utime.tv_usec + u.ru_stime.tv_usec);
}

std::string load_average() {
    std::ifstream in("/proc/loadavg");
    std::string one, five, fifteen;
    in >> one >> five >> fifteen;
    return one.empty() ? "unknown" : one + " " + five + " " + fifteen;
}

//! One check's solves from its report.json (fem.solves), one phrase each.
std::string solves_of(const std::string& out_dir, std::int64_t id) {
    std::ifstream in(out_dir + "/verify/individual-" + std::to_string(id) + "/report.json");
    if (!in) return "no report.json";
    try {
        const auto j = nlohmann::json::parse(in);
        std::string text;
        char line[200];
        for (const auto& s : j.at("fem").at("solves")) {
            std::snprintf(line, sizeof line, "%s%s %s%s, %d elements: %.1f s CPU (deck %.2f s)",
                          text.empty() ? "" : "; ", s.at("mesh").get<std::string>().c_str(),
                          s.at("nlgeom").get<bool>() ? "nonlinear " : "linear",
                          s.at("law").is_null() ? "" : s.at("law").get<std::string>().c_str(),
                          s.at("elements").get<int>(), s.at("cpu_s").get<double>(),
                          s.at("deck_s").get<double>());
            text += line;
        }
        std::snprintf(line, sizeof line, "; our engine %.1f s CPU",
                      j.at("engine").at("cpu_s").get<double>());
        return text + line;
    } catch (const std::exception& e) {
        return std::string("unreadable report.json: ") + e.what();
    }
}

//! The CalculiX checker, timed: wall time of each check on the job's thread, and its CPU time
//! (the thread's own and ccx's).
class TimedChecker final : public ContinuumChecker {
  public:
    std::optional<LoopCheck> check(const Experiment& rules, const LoopCheckRequest& body,
                                   const std::string& out_dir,
                                   const std::atomic<bool>& cancel) override {
        const auto start = std::chrono::steady_clock::now();
        const double thread_before = thread_cpu_s(), ccx_before = process_cpu_s(RUSAGE_CHILDREN);
        auto result = inner_.check(rules, body, out_dir, cancel);
        const double thread_s = thread_cpu_s() - thread_before;
        const double ccx_s = process_cpu_s(RUSAGE_CHILDREN) - ccx_before;
        std::lock_guard lock(mutex_);
        wall_s_ += seconds_since(start);
        thread_cpu_s_ += thread_s;
        ccx_cpu_s_ += ccx_s;
        ++checks_;
        if (result)
            std::fprintf(stderr,
                         "  check of individual %lld: %s (%.1f s wall, %.1f s CPU: ccx %.1f, the "
                         "check's thread %.1f)\n    %s\n",
                         static_cast<long long>(body.id), result->verdict.c_str(),
                         seconds_since(start), ccx_s + thread_s, ccx_s, thread_s,
                         solves_of(out_dir, body.id).c_str());
        return result;
    }
    std::string unavailable() const override { return inner_.unavailable(); }
    double wall_s() const { return wall_s_; }
    double cpu_s() const { return thread_cpu_s_ + ccx_cpu_s_; }
    int checks() const { return checks_; }

  private:
    CalculixChecker inner_;
    std::mutex mutex_;
    double wall_s_ = 0.0, thread_cpu_s_ = 0.0, ccx_cpu_s_ = 0.0;
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
        const std::string load_before = load_average();
        std::fprintf(stderr, "load average at the start: %s\n", load_before.c_str());
        std::vector<double> plain_cpu;  // the evaluation's CPU per generation (no checks)
        auto run_all = [&](EvolutionRun& run, const char* label, std::vector<double>* cpu) {
            std::vector<double> times;
            for (int g = 0; g < generations; ++g) {
                const auto start = std::chrono::steady_clock::now();
                const double cpu_before = process_cpu_s(RUSAGE_SELF);
                if (!run.run_generation()) throw std::runtime_error("a generation was abandoned");
                times.push_back(seconds_since(start));
                if (cpu) cpu->push_back(process_cpu_s(RUSAGE_SELF) - cpu_before);
                std::fprintf(stderr, "%s generation %d: %.1f s\n", label, g, times.back());
            }
            return times;
        };
        const std::vector<double> plain_t = run_all(plain, "without checks", &plain_cpu);
        const std::vector<double> checked_t = run_all(with_checks, "with checks", nullptr);
        const std::string load_after = load_average();
        double plain_s = 0.0, checked_s = 0.0, plain_window = 0.0, checked_window = 0.0;
        double window_cpu = 0.0;
        int window_generations = 0;
        for (int g = 0; g < generations; ++g) {
            plain_s += plain_t[g];
            checked_s += checked_t[g];
            if (g >= every && g < 2 * every) {
                plain_window += plain_t[g];
                checked_window += checked_t[g];
                window_cpu += plain_cpu[g];
                ++window_generations;
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
        // The checks' CPU per generation (one batch per period of `every`) against the
        // evaluation's per generation in steady state.
        // (batches started: picked after generations every-1, 2 every-1, ... before the last)
        const int batches = std::max(1, (generations - 1) / std::max(1, every));
        const double check_cpu_per_generation = checker->cpu_s() / (batches * every);
        const double eval_cpu_per_generation =
            window_generations > 0 ? window_cpu / window_generations : 0.0;
        const double cpu_ratio = eval_cpu_per_generation > 0.0
                                     ? check_cpu_per_generation / eval_cpu_per_generation
                                     : 0.0;
        std::fprintf(stderr,
                     "CPU: the checks %.1f s in all (%d batch%s), %.1f s per generation, against "
                     "the evaluation's %.1f s per generation (generations %d-%d without checks): "
                     "%.1f %%\nload average at the start %s, at the end %s\n",
                     checker->cpu_s(), batches, batches == 1 ? "" : "es", check_cpu_per_generation,
                     eval_cpu_per_generation, every, 2 * every - 1, 100.0 * cpu_ratio,
                     load_before.c_str(), load_after.c_str());
        std::fprintf(stderr,
                     "%s: %d generations, %d checks (%.1f s of check wall time): %.1f s without, "
                     "%.1f s with checks: overhead %+.1f %% over the run, %+.1f %% over "
                     "generations %d-%d (one period in steady state)\n",
                     e.name.c_str(), generations, checker->checks(), checker->wall_s(), plain_s,
                     checked_s, 100.0 * overhead, 100.0 * window_overhead, every,
                     2 * every - 1);
        const char* commit_env = std::getenv("BHM_COMMIT");  // scripts/bench.sh sets it
        std::printf(
            "machine,commit,experiment,population,generations,every,top,threads,checks,"
            "check_wall_s,plain_s,checked_s,overhead,window_overhead,check_cpu_s,"
            "eval_cpu_per_generation_s,cpu_ratio,load_start,load_end\n");
        std::printf("%s,%s,%s,%d,%d,%d,%d,%d,%d,%.2f,%.2f,%.2f,%.4f,%.4f,%.2f,%.2f,%.4f,%s,%s\n",
                    machine_description().c_str(),
                    arg_text(argc, argv, "--commit", commit_env ? commit_env : "unknown").c_str(),
                    e.name.c_str(), e.evolution.population, generations,
                    checked.evolution.verify.every_generations, checked.evolution.verify.top_k,
                    threads, checker->checks(), checker->wall_s(), plain_s, checked_s, overhead,
                    window_overhead, checker->cpu_s(), eval_cpu_per_generation, cpu_ratio,
                    load_before.substr(0, load_before.find(' ')).c_str(),
                    load_after.substr(0, load_after.find(' ')).c_str());
        return 0;
    } catch (const std::exception& error) {
        std::fprintf(stderr, "bench_loop_verify: %s\n", error.what());
        return 1;
    }
}
