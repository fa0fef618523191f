#include "evo/run/batch.hpp"

#include <chrono>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <stdexcept>
#include <thread>

#include "engine/io/text_file.hpp"
#include "evo/experiment/experiment_io.hpp"
#include "evo/experiment/json_reader.hpp"
#include "evo/formats/vxa.hpp"
#include "evo/run/checkpoint.hpp"

namespace bhm::evo {

namespace fs = std::filesystem;

std::string batch_run_dir(const std::string& dir, int k) {
    char name[16];
    std::snprintf(name, sizeof name, "run-%02d", k);
    return (fs::path(dir) / name).string();
}

double student_t_975(int df) {
    // Two-sided 95 % (0.975 quantile), df = 1..30, from the t distribution's standard table.
    static constexpr double kTable[30] = {12.706, 4.303, 3.182, 2.776, 2.571, 2.447, 2.365, 2.306,
                                          2.262,  2.228, 2.201, 2.179, 2.160, 2.145, 2.131, 2.120,
                                          2.110,  2.101, 2.093, 2.086, 2.080, 2.074, 2.069, 2.064,
                                          2.060,  2.056, 2.052, 2.048, 2.045, 2.042};
    if (df < 1) throw std::invalid_argument("Student's t needs df >= 1");
    return df <= 30 ? kTable[df - 1] : 1.96;
}

std::string batch_csv(const std::vector<std::vector<HistoryRow>>& histories) {
    std::string out = "generation";
    for (std::size_t k = 0; k < histories.size(); ++k) {
        char name[32];
        std::snprintf(name, sizeof name, ",run_%02zu", k + 1);
        out += name;
    }
    out += ",runs,mean,ci95_low,ci95_high\n";
    std::size_t generations = 0;
    for (const auto& h : histories)
        generations = std::max(generations, h.size());
    for (std::size_t g = 0; g < generations; ++g) {
        out += std::to_string(g);
        std::vector<double> best;
        for (const auto& h : histories) {
            out += ",";
            if (g < h.size()) {
                out += engine::format_number(h[g].best_fitness);
                best.push_back(h[g].best_fitness);
            }
        }
        const auto n = static_cast<double>(best.size());
        double mean = 0.0;
        for (double b : best)
            mean += b / n;
        double half_width = 0.0;
        if (best.size() > 1) {
            double ss = 0.0;
            for (double b : best)
                ss += (b - mean) * (b - mean);
            half_width = student_t_975(static_cast<int>(best.size()) - 1) *
                         std::sqrt(ss / (n - 1.0)) / std::sqrt(n);
        }
        out += "," + std::to_string(best.size()) + "," + engine::format_number(mean) + "," +
               engine::format_number(mean - half_width) + "," +
               engine::format_number(mean + half_width) + "\n";
    }
    return out;
}

namespace {

nlohmann::json read_json(const fs::path& path) {
    const std::string text = engine::read_text(path.string(), engine::kTextFileCap);
    try {
        return nlohmann::json::parse(text);
    } catch (const nlohmann::json::exception& e) {
        throw std::runtime_error(path.string() + ": not valid JSON (" +
                                 without_json_tags(e.what()) + ")");
    }
}

}  // namespace

BatchRun::BatchRun(const Experiment& experiment, BatchOptions options, bool resume)
    : experiment_(experiment), options_(std::move(options)), resume_(resume) {
    if (options_.out_dir.empty()) throw std::invalid_argument("a batch needs --out DIR");
    const fs::path info = fs::path(options_.out_dir) / kBatchFile;
    if (resume_ && fs::exists(info)) {
        const auto j = read_json(info);
        if (!j.contains("runs") || !j["runs"].is_number_integer() || !j.contains("base_seed") ||
            !j["base_seed"].is_number_unsigned())
            throw std::runtime_error(info.string() + ": expected {\"runs\": N, \"base_seed\": S}");
        const int runs = j["runs"].get<int>();
        if (options_.runs != runs)
            throw std::invalid_argument("--runs " + std::to_string(options_.runs) + " but " +
                                        info.string() + " says " + std::to_string(runs));
        base_seed_ = j["base_seed"].get<std::uint64_t>();
        if (options_.run.seed && *options_.run.seed != base_seed_)
            throw std::invalid_argument("--seed differs from the batch's base seed " +
                                        std::to_string(base_seed_));
    } else {
        if (!resume_ && fs::exists(info))
            throw std::runtime_error(options_.out_dir +
                                     ": already holds a batch (batch.json); continue it with "
                                     "--resume or choose another --out");
        base_seed_ = options_.run.seed.value_or(experiment_.evolution.seed);
    }
    if (options_.runs < 1 || options_.runs > 99)
        throw std::invalid_argument("--runs must be in [1, 99]");
    std::error_code ec;
    fs::create_directories(options_.out_dir, ec);
    if (ec)
        throw std::runtime_error(options_.out_dir + ": cannot create the batch directory (" +
                                 ec.message() + ")");
    write_file_atomically(info.string(), nlohmann::json{{"runs", options_.runs},
                                                        {"base_seed", base_seed_},
                                                        {"experiment", experiment_.name}}
                                                 .dump(2) +
                                             "\n");
}

StopReason BatchRun::run() {
    std::vector<std::vector<HistoryRow>> histories;
    StopReason reason = StopReason::GenerationBudget;
    const auto write_csv = [&] {
        write_file_atomically((fs::path(options_.out_dir) / kBatchCsvFile).string(),
                              batch_csv(histories));
    };
    for (int k = 1; k <= options_.runs; ++k) {
        RunOptions o = options_.run;
        o.out_dir = batch_run_dir(options_.out_dir, k);
        o.seed = base_seed_ + static_cast<std::uint64_t>(k - 1);
        std::unique_ptr<EvolutionRun> run;
        const bool has_checkpoint = fs::exists(fs::path(o.out_dir) / kCheckpointFile) ||
                                    fs::exists(fs::path(o.out_dir) / kPreviousCheckpointFile);
        if (resume_ && has_checkpoint) {
            run = EvolutionRun::resume(o);
            for (const auto& w : run->resume_warnings())
                warnings_.push_back(o.out_dir + ": " + w);
        } else {
            run = std::make_unique<EvolutionRun>(experiment_, o);
        }
        if (callback_)
            run->set_report_callback([this, k](std::shared_ptr<const GenerationReport> r) {
                callback_(k, std::move(r));
            });
        // A signal handler can only store to one flag: forward the batch's to the current run.
        std::atomic<bool> finished{false};
        std::thread forward([&] {
            while (!finished.load()) {
                if (stop_.load()) run->request_stop();
                std::this_thread::sleep_for(std::chrono::milliseconds(20));
            }
        });
        try {
            reason = stop_.load() ? StopReason::StopRequested : run->run();
        } catch (...) {
            finished.store(true);
            forward.join();
            throw;
        }
        finished.store(true);
        forward.join();
        histories.push_back(run->state().history);
        write_csv();
        if (reason == StopReason::StopRequested) return reason;
    }
    return reason;
}

}  // namespace bhm::evo
