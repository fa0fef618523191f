// evolution.algorithm = "novelty" end to end on a tiny workspace: the archive grows and the
// population is chosen by novelty, the champion is the best fitness ever simulated (selected or
// not), fitness.csv carries the novelty columns, and a stopped-then-resumed run equals its
// uninterrupted twin (archive included).
#include <doctest/doctest.h>
#include <unistd.h>

#include <algorithm>
#include <filesystem>
#include <fstream>
#include <memory>
#include <sstream>

#include "evo/evaluate/behaviour.hpp"
#include "evo/experiment/experiment_io.hpp"
#include "evo/run/checkpoint.hpp"
#include "evo/run/evolution_run.hpp"
#include "evo_test_support.hpp"
#include "run_test_support.hpp"
#include "support/scratch.hpp"

using namespace bhm::evo;
namespace fs = std::filesystem;

namespace {

Experiment novelty_experiment() {
    auto e = test::tiny_experiment();
    e.evolution.algorithm = Algorithm::Novelty;
    e.evolution.novelty.k = 3;
    e.evolution.novelty.archive_threshold = 0.01;  // tiny bodies move little: let the archive fill
    e.evolution.novelty.archive_capacity = 12;
    return e;
}

RunOptions options(int generations, int threads, const std::string& dir = "",
                   std::shared_ptr<Evaluator> evaluator = nullptr) {
    return test::run_options(generations, threads, dir, std::move(evaluator));
}

fs::path fresh_dir(const std::string& name) {
    return test::fresh_dir("novelty", name);
}

using test::without_wall;

//! Every simulated fitness, in the order the run asked for them.
class RecordingEvaluator final : public Evaluator {
  public:
    void evaluate(const EvaluationBatch& batch, std::vector<FitnessReport>& results) override {
        inner_.evaluate(batch, results);
        for (const auto& r : results)
            fitness.push_back(r.fitness);
    }
    int concurrency() const override { return 1; }
    std::vector<double> fitness;

  private:
    ThreadEvaluator inner_{1};
};

}  // namespace

TEST_CASE("a novelty run selects by novelty, fills its archive and keeps the fittest champion") {
    const auto e = novelty_experiment();
    auto recorder = std::make_shared<RecordingEvaluator>();
    EvolutionRun run(e, options(5, 1, "", recorder));
    std::vector<std::shared_ptr<const GenerationReport>> reports;
    run.set_report_callback([&](auto r) { reports.push_back(r); });
    run.run();
    const auto& s = run.state();
    REQUIRE(s.history.size() == 5u);
    REQUIRE(reports.size() == 5u);

    // The archive took entries, each a whole descriptor, and never beyond its capacity.
    CHECK_FALSE(s.novelty_archive.entries.empty());
    CHECK(s.novelty_archive.entries.size() <= 12u);
    for (const auto& entry : s.novelty_archive.entries)
        CHECK(entry.size() == static_cast<std::size_t>(kBehaviourLength));
    for (const auto& h : s.history) {
        REQUIRE(h.novelty);
        CHECK(h.novelty->archive_size <= 12);
        CHECK(h.novelty->best_novelty >= h.novelty->median_novelty);
        CHECK(h.novelty->archive_threshold > 0.0);
    }
    CHECK(s.history.back().novelty->archive_size ==
          static_cast<int>(s.novelty_archive.entries.size()));

    // The population is in novelty order within its first layer: the report's first member is
    // the most novel of that layer.
    const auto& last = *reports.back();
    REQUIRE(last.novelty);
    CHECK(last.population.front().novelty == last.novelty->best_novelty);

    // The champion is the best fitness of every simulation the run made, kept or not.
    REQUIRE(s.champion);
    const double best_simulated =
        *std::max_element(recorder->fitness.begin(), recorder->fitness.end());
    CHECK(s.champion->individual.report.fitness == best_simulated);
    CHECK(s.history.back().novelty->champion_fitness == best_simulated);
    for (const auto& h : s.history)
        CHECK(h.best_fitness <= s.champion->individual.report.fitness);

    // The same experiment under AFPO makes another run: novelty changed what survived.
    auto afpo = e;
    afpo.evolution.algorithm = Algorithm::Afpo;
    EvolutionRun twin(afpo, options(5, 1));
    twin.run();
    std::vector<std::int64_t> a, b;
    for (const auto& m : s.population)
        a.push_back(m.id);
    for (const auto& m : twin.state().population)
        b.push_back(m.id);
    CHECK(a != b);
}

TEST_CASE("a stopped novelty run resumes into its uninterrupted twin, archive included") {
    const auto e = novelty_experiment();
    const fs::path whole = fresh_dir("whole"), parts = fresh_dir("parts");
    EvolutionRun uninterrupted(e, options(5, 2, whole.string()));
    uninterrupted.run();
    auto resumed = test::stopped_then_resumed(e, parts.string(), 5, 2, 2);
    REQUIRE(resumed);
    CHECK(resumed->resume_warnings().empty());
    CHECK(resumed->state().generation == 2);
    CHECK(resumed->state().novelty_archive.entries.size() > 0u);
    resumed->run();

    const auto& u = uninterrupted.state();
    const auto& r = resumed->state();
    CHECK(r.novelty_archive == u.novelty_archive);
    CHECK(without_wall(r.history) == without_wall(u.history));
    CHECK(r.rng == u.rng);
    REQUIRE(r.champion);
    CHECK(r.champion->individual.genome == u.champion->individual.genome);
    REQUIRE(r.population.size() == u.population.size());
    for (std::size_t i = 0; i < u.population.size(); ++i) {
        CHECK(r.population[i].id == u.population[i].id);
        CHECK(r.population[i].report.behaviour == u.population[i].report.behaviour);
    }

    // fitness.csv: the novelty columns after the usual ones, one row per generation.
    std::ifstream csv(whole / "fitness.csv");
    std::string header, row;
    std::getline(csv, header);
    CHECK(header == std::string(kFitnessCsvHeader) +
                        ",best_novelty,median_novelty,archive_size,archive_added,"
                        "archive_threshold,champion_fitness");
    int rows = 0;
    while (std::getline(csv, row))
        ++rows;
    CHECK(rows == 5);

    // A checkpoint without its archive is refused by name, not resumed into another run.
    resumed.reset();
    std::vector<std::string> notes;
    auto payload = parse_checkpoint_text(bhm::test::read_file(parts / kCheckpointFile), notes);
    payload.erase("novelty_archive");
    CHECK_THROWS_WITH(run_state_from_json(payload, "cp.json"),
                      doctest::Contains("novelty_archive"));
    fs::remove_all(whole);
    fs::remove_all(parts);
}
