#pragma once
// Batches of independent runs (paper section 4.3 compared 10 independent runs, Figure 14):
// `bhm evolve EXP --out DIR --runs N`. Run k (1-based) is an ordinary run directory DIR/run-kk
// with seed base + k - 1 (base = --seed or evolution.seed), so each is exactly the run `bhm evolve
// --seed base+k-1` would make alone. The runs go one after another, each using the whole worker
// pool (parallelism inside a generation already fills it). DIR/batch.json records the run count
// and base seed; DIR/batch.csv has, per generation, each run's best fitness, the number of runs
// that reached it, their mean and a 95 % confidence interval of the mean (Student's t,
// mean +- t(0.975, n - 1) s / sqrt(n); the interval is the mean itself for n = 1). --resume
// resumes every run that has a checkpoint and starts the others.
#include <atomic>
#include <cstdint>
#include <functional>
#include <memory>
#include <string>
#include <vector>

#include "evo/run/evolution_run.hpp"

namespace bhm::evo {

inline constexpr const char* kBatchFile = "batch.json";
inline constexpr const char* kBatchCsvFile = "batch.csv";

struct BatchOptions {
    std::string out_dir;
    int runs = 1;    //!< [1, 99]
    RunOptions run;  //!< budgets, threads, base seed; run.out_dir is set per run
};

//! DIR/run-kk (k from 1, two digits).
std::string batch_run_dir(const std::string& dir, int k);
//! 97.5 % quantile of Student's t with df degrees of freedom (df >= 1; 1.96 beyond a table of 30).
double student_t_975(int df);
//! batch.csv text from each run's history: generation,run_01..run_NN,runs,mean,ci95_low,ci95_high
//! (a run that has not reached a generation leaves its cell empty).
std::string batch_csv(const std::vector<std::vector<HistoryRow>>& histories);

using BatchReportCallback =
    std::function<void(int run, std::shared_ptr<const GenerationReport> report)>;

class BatchRun {
  public:
    //! resume = false refuses a DIR whose batch.json or run directories already hold runs.
    //! Throws std::invalid_argument / std::runtime_error naming the file.
    BatchRun(const Experiment& experiment, BatchOptions options, bool resume);

    //! Runs (or continues) every run in turn; returns the first run's stop reason that is not a
    //! budget (a stop request), else the last run's. Writes batch.csv after each run.
    StopReason run();
    void set_report_callback(BatchReportCallback callback) { callback_ = std::move(callback); }
    //! Raised from a signal handler: the run in progress stops as on its own stop flag.
    std::atomic<bool>& stop_flag() { return stop_; }
    int runs() const { return options_.runs; }
    std::uint64_t base_seed() const { return base_seed_; }
    //! Warnings from resumed runs, prefixed with their directory.
    const std::vector<std::string>& warnings() const { return warnings_; }

  private:
    Experiment experiment_;
    BatchOptions options_;
    bool resume_;
    std::uint64_t base_seed_ = 0;
    std::atomic<bool> stop_{false};
    BatchReportCallback callback_;
    std::vector<std::string> warnings_;
};

}  // namespace bhm::evo
