// Batches of runs (evo/run/batch.hpp): a 2-run batch equals the two runs made alone, batch.csv's
// statistics against numbers worked out by hand, resume of a stopped batch.
#include <doctest/doctest.h>
#include <unistd.h>

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <sstream>

#include "evo/run/batch.hpp"
#include "evo/run/checkpoint.hpp"
#include "evo_test_support.hpp"
#include "support/scratch.hpp"

using namespace bhm::evo;
namespace fs = std::filesystem;

namespace {

std::vector<HistoryRow> without_wall(std::vector<HistoryRow> rows) {
    for (auto& r : rows)
        r.wall_s = 0.0;
    return rows;
}

}  // namespace

TEST_CASE("batch.csv: each run's best, the mean and Student's 95 % interval") {
    std::vector<std::vector<HistoryRow>> h(3);
    const double best[3][2] = {{1.0, 2.0}, {3.0, 4.0}, {5.0, 9.0}};
    for (int k = 0; k < 3; ++k)
        for (int g = 0; g < (k == 2 ? 1 : 2); ++g) {  // run 3 stopped after generation 0
            HistoryRow r;
            r.generation = g;
            r.best_fitness = best[k][g];
            h[static_cast<std::size_t>(k)].push_back(r);
        }
    // Generation 0: 1, 3, 5: mean 3, s = 2, t(0.975, 2) = 4.303: 3 -+ 4.303 * 2 / sqrt(3).
    // Generation 1: 2, 4 (two runs): mean 3, s = sqrt(2), t(0.975, 1) = 12.706: 3 -+ 12.706.
    const double w0 = 4.303 * 2.0 / std::sqrt(3.0);
    const std::string csv = batch_csv(h);
    std::istringstream in(csv);
    std::string header, row0, row1;
    std::getline(in, header);
    std::getline(in, row0);
    std::getline(in, row1);
    CHECK(header == "generation,run_01,run_02,run_03,runs,mean,ci95_low,ci95_high");
    CHECK(row0.rfind("0,1,3,5,3,3,", 0) == 0);
    CHECK(row1.rfind("1,2,4,,2,3,", 0) == 0);
    auto last_two = [](const std::string& row) {
        const auto b = row.rfind(','), a = row.rfind(',', b - 1);
        return std::make_pair(std::stod(row.substr(a + 1, b - a - 1)),
                              std::stod(row.substr(b + 1)));
    };
    CHECK(last_two(row0).first == doctest::Approx(3.0 - w0));
    CHECK(last_two(row0).second == doctest::Approx(3.0 + w0));
    CHECK(last_two(row1).first == doctest::Approx(3.0 - 12.706));
    CHECK(student_t_975(40) == 1.96);
}

TEST_CASE("a 2-run batch equals the two runs made alone, and resumes to the same result") {
    const auto e = test::tiny_experiment();
    const fs::path dir = bhm::test::scratch_dir("batch-two", false);
    BatchOptions b;
    b.out_dir = dir.string();
    b.runs = 2;
    b.run.generations = 3;
    b.run.threads = 2;
    b.run.seed = 40;
    BatchRun(e, b, false).run();
    CHECK_THROWS_AS(BatchRun(e, b, false), std::runtime_error);  // DIR already holds a batch

    for (int k = 1; k <= 2; ++k) {
        RunOptions alone;
        alone.generations = 3;
        alone.threads = 1;
        alone.seed = 40 + static_cast<std::uint64_t>(k - 1);
        EvolutionRun run(e, alone);
        run.run();
        const auto loaded = load_checkpoint(batch_run_dir(dir.string(), k));
        CHECK(loaded.state.seed == 40 + static_cast<std::uint64_t>(k - 1));
        CHECK(without_wall(loaded.state.history) == without_wall(run.state().history));
        CHECK(loaded.state.champion->individual.genome == run.state().champion->individual.genome);
    }
    const std::string csv = bhm::test::read_file(dir / kBatchCsvFile);
    CHECK(std::count(csv.begin(), csv.end(), '\n') == 4);  // header + generations 0..2

    // A batch stopped before its second run, then resumed, ends with the same batch.csv.
    const fs::path part = bhm::test::scratch_dir("batch-resume", false);
    b.out_dir = part.string();
    {
        BatchRun first(e, b, false);
        first.set_report_callback([&](int run, std::shared_ptr<const GenerationReport>) {
            if (run == 1) first.stop_flag().store(true);
        });
        CHECK(first.run() == StopReason::StopRequested);
    }
    CHECK_FALSE(fs::exists(fs::path(batch_run_dir(part.string(), 2)) / kCheckpointFile));
    BatchRun(e, b, true).run();
    CHECK(bhm::test::read_file(part / kBatchCsvFile) == csv);
    fs::remove_all(dir);
    fs::remove_all(part);
}
