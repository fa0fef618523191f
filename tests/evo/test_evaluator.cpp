// The evaluation interface: the in-process ThreadEvaluator returns exactly evaluate_body's reports,
// a run over any Evaluator that does so is the same run, and an evaluator that fails mid-batch
// abandons the generation without touching the state (what a lost MPI rank looks like to evo/).
#include <doctest/doctest.h>

#include <algorithm>
#include <mutex>
#include <stdexcept>

#include "evo/evaluate/evaluator.hpp"
#include "evo/run/evolution_run.hpp"
#include "evo_test_support.hpp"
#include "run_test_support.hpp"

using namespace bhm::evo;
using bhm::evo::test::run_options;
using bhm::evo::test::without_wall;

namespace {

//! Evaluates a batch last body first, counting what it was given: a stand-in for a remote
//! evaluator whose results arrive in any order.
class ReverseEvaluator final : public Evaluator {
  public:
    void evaluate(const EvaluationBatch& batch, std::vector<FitnessReport>& results) override {
        results.assign(batch.bodies.size(), FitnessReport{});
        for (std::size_t k = batch.bodies.size(); k-- > 0;)
            results[k] = evaluate_body(*batch.rules, *batch.bodies[k], batch.cancel);
        ++batches;
        bodies += static_cast<int>(batch.bodies.size());
    }
    int concurrency() const override { return 1; }
    int batches = 0;
    int bodies = 0;
};

//! Succeeds for `good_batches` batches, then fails as a lost rank would.
class FailingEvaluator final : public Evaluator {
  public:
    explicit FailingEvaluator(int good_batches) : good_(good_batches) {}
    void evaluate(const EvaluationBatch& batch, std::vector<FitnessReport>& results) override {
        if (good_-- <= 0) throw std::runtime_error("rank 1 is gone");
        inner_.evaluate(batch, results);
    }
    int concurrency() const override { return 1; }

  private:
    int good_;
    ThreadEvaluator inner_{1};
};

}  // namespace

TEST_CASE("ThreadEvaluator returns evaluate_body's reports in batch order, one callback each") {
    const auto e = test::tiny_experiment();
    const Developer developer(e);
    Rng rng(3);
    std::vector<Phenotype> phenotypes;
    while (phenotypes.size() < 5) {
        auto p = developer.develop(random_genome(e.evolution.cppn, rng));
        if (p.voxels > 0) phenotypes.push_back(std::move(p));  // an empty body cannot be simulated
    }
    EvaluationBatch batch;
    batch.rules = &e;
    for (const auto& p : phenotypes)
        batch.bodies.push_back(&p.body);
    std::mutex mutex;
    std::vector<std::size_t> called;
    batch.on_result = [&](std::size_t i) {
        std::lock_guard lock(mutex);
        called.push_back(i);
    };
    std::vector<FitnessReport> results;
    ThreadEvaluator(2).evaluate(batch, results);
    REQUIRE(results.size() == phenotypes.size());
    for (std::size_t i = 0; i < phenotypes.size(); ++i) {
        const auto direct = evaluate_body(e, phenotypes[i].body);
        CHECK(results[i].measures == direct.measures);
        CHECK(results[i].fitness == direct.fitness);
        CHECK(results[i].steps == direct.steps);
    }
    std::sort(called.begin(), called.end());
    CHECK(called == std::vector<std::size_t>{0, 1, 2, 3, 4});

    // A raised cancel flag abandons the batch.
    std::atomic<bool> cancel{true};
    batch.cancel = &cancel;
    CHECK_THROWS_AS(ThreadEvaluator(2).evaluate(batch, results), EvaluationCancelled);
}

TEST_CASE("a run over another Evaluator is the same run as over the thread pool") {
    const auto e = test::tiny_experiment();
    EvolutionRun pooled(e, run_options(3, 2, "", nullptr));
    auto reverse = std::make_shared<ReverseEvaluator>();
    EvolutionRun custom(e, run_options(3, 2, "", reverse));
    pooled.run();
    custom.run();
    CHECK(reverse->batches == 3);
    int simulations = 0;
    for (const auto& row : custom.state().history)
        simulations += row.simulations;
    CHECK(reverse->bodies == simulations);
    CHECK(without_wall(pooled.state().history) == without_wall(custom.state().history));
    REQUIRE(custom.state().champion);
    CHECK(custom.state().champion->individual.genome == pooled.state().champion->individual.genome);
    CHECK(custom.state().rng == pooled.state().rng);
}

TEST_CASE("an evaluator failure abandons the generation and keeps the last complete state") {
    const auto e = test::tiny_experiment();
    EvolutionRun run(e, run_options(4, 2, "", std::make_shared<FailingEvaluator>(2)));
    CHECK_THROWS_WITH_AS(run.run(), doctest::Contains("rank 1 is gone"), std::runtime_error);
    CHECK(run.state().generation == 1);  // generations 0 and 1 completed, 2 was abandoned
    CHECK(run.state().history.size() == 2);
}
