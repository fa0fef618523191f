// The AFPO run loop end to end on a tiny workspace: pool sizes and ages, elitism, determinism
// across thread counts, stop and resume equivalence, checkpoint fallback, rule changes, files.
#include <doctest/doctest.h>
#include <unistd.h>

#include <chrono>
#include <filesystem>
#include <fstream>
#include <set>
#include <sstream>
#include <thread>

#include "evo/evaluate/constraints.hpp"
#include "evo/run/checkpoint.hpp"
#include "evo/run/evolution_run.hpp"
#include "evo/run/run_lock.hpp"
#include "evo_test_support.hpp"
#include "run_test_support.hpp"
#include "support/scratch.hpp"
#include "xml_check.hpp"

using namespace bhm::evo;
namespace fs = std::filesystem;
using bhm::evo::test::csv_without_wall;
using bhm::evo::test::run_options;
using bhm::evo::test::without_wall;

namespace {}  // namespace

TEST_CASE("AFPO generations: pool 2P+1 cut to P, ages, newcomers, elitism") {
    const auto e = test::tiny_experiment();
    const int P = e.evolution.population;
    EvolutionRun run(e, run_options(4, 2));
    std::vector<std::shared_ptr<const GenerationReport>> reports;
    run.set_report_callback([&](auto r) { reports.push_back(r); });
    CHECK(run.run() == StopReason::GenerationBudget);
    REQUIRE(reports.size() == 4);

    double best_so_far = -1e300;
    for (const auto& r : reports) {
        CAPTURE(r->generation);
        CHECK(static_cast<int>(r->population.size()) == P);
        // Generation 0: P random individuals; later: P mutants plus one newcomer.
        CHECK(r->evaluations == (r->generation == 0 ? P : P + 1));
        CHECK(r->simulations + r->cache_hits == r->evaluations);
        CHECK(r->simulations <= r->evaluations);
        CHECK(r->best_fitness >= best_so_far);  // the best is always non-dominated: never lost
        best_so_far = r->best_fitness;
        CHECK(r->champion.individual.report.fitness == doctest::Approx(r->best_fitness));
        for (const auto& m : r->population) {
            CHECK(m.age >= 0);
            CHECK(m.age <= r->generation);  // ages grow by one per generation at most
            CHECK(m.fitness <= r->best_fitness);
            CHECK(m.pareto_rank >= 0);
            CHECK(m.valid);
        }
        std::set<std::int64_t> ids;
        for (const auto& m : r->population)
            ids.insert(m.id);
        CHECK(ids.size() == static_cast<std::size_t>(P));  // no duplicates
        if (r->generation > 0) {
            // Only the newcomer has age 0 (mutants inherit their parent's age, which is >= 1), and
            // nobody is younger, so it is never dominated: it survives in layer 0.
            int newborns = 0;
            for (const auto& m : r->population)
                if (m.age == 0) {
                    ++newborns;
                    CHECK(m.pareto_rank == 0);
                    CHECK(m.id == P + r->generation * (P + 1) - 1);  // the generation's last id
                }
            CHECK(newborns == 1);
        }
    }
    // Ages: a survivor of generation g-1 is exactly one older in generation g.
    for (std::size_t k = 1; k < reports.size(); ++k)
        for (const auto& m : reports[k]->population)
            for (const auto& old : reports[k - 1]->population)
                if (old.id == m.id) CHECK(m.age == old.age + 1);
    const auto& state = run.state();
    CHECK(state.history.size() == 4);
    CHECK(state.next_id == P + 3 * (P + 1));
    for (const auto& m : state.population) {
        CHECK(m.phenotype == run.developer().develop(m.genome));
        CHECK(constraint_violation(e.fitness.constraints, e.boundary, run.developer().space(),
                                   m.phenotype)
                  .empty());
    }
}

TEST_CASE("the same seed gives the same run with 1 and 2 threads") {
    const auto e = test::tiny_experiment();
    EvolutionRun one(e, run_options(3, 1));
    EvolutionRun two(e, run_options(3, 2));
    one.run();
    two.run();
    CHECK(without_wall(one.state().history) == without_wall(two.state().history));
    REQUIRE(one.state().champion);
    REQUIRE(two.state().champion);
    CHECK(one.state().champion->individual.genome == two.state().champion->individual.genome);
    CHECK(one.state().champion->individual.report.fitness ==
          two.state().champion->individual.report.fitness);
    CHECK(one.state().rng == two.state().rng);
    // A different seed gives a different run.
    auto other = run_options(3, 2);
    other.seed = 8;
    EvolutionRun three(e, other);
    three.run();
    CHECK(three.state().champion->individual.genome != one.state().champion->individual.genome);
}

TEST_CASE("stop, then resume, is identical to an uninterrupted run") {
    const auto e = test::tiny_experiment();
    const fs::path whole = bhm::test::scratch_dir("evo-whole", false),
                   parts = bhm::test::scratch_dir("evo-parts", false);
    EvolutionRun uninterrupted(e, run_options(4, 2, whole.string()));
    uninterrupted.run();

    {
        EvolutionRun first(e, run_options(4, 1, parts.string()));
        first.set_report_callback([&](auto r) {
            if (r->generation == 1) first.request_stop();  // as Ctrl-C would, between generations
        });
        CHECK(first.run() == StopReason::StopRequested);
        CHECK(first.state().generation == 1);
    }
    auto resumed = EvolutionRun::resume(run_options(4, 2, parts.string()));
    CHECK(resumed->resume_warnings().empty());
    CHECK(resumed->state().generation == 1);
    CHECK(resumed->run() == StopReason::GenerationBudget);

    CHECK(csv_without_wall(bhm::test::read_file(parts / "fitness.csv")) ==
          csv_without_wall(bhm::test::read_file(whole / "fitness.csv")));
    CHECK(resumed->state().champion->individual.genome ==
          uninterrupted.state().champion->individual.genome);
    CHECK(resumed->state().rng == uninterrupted.state().rng);
    CHECK(resumed->state().cache.insertion_order() ==
          uninterrupted.state().cache.insertion_order());
    for (std::size_t i = 0; i < uninterrupted.state().population.size(); ++i)
        CHECK(resumed->state().population[i].id == uninterrupted.state().population[i].id);

    // The run directory holds every promised file.
    for (const char* name : {"run.json", "fitness.csv", "champion.json", "champion.vxa",
                             "checkpoint.json", "checkpoint.prev.json", "champions/gen-00000.json"})
        CHECK_MESSAGE(fs::exists(whole / name), name);
    CHECK(bhm::test::read_file(whole / "fitness.csv").rfind(kFitnessCsvHeader, 0) == 0);
    const auto run_json = nlohmann::json::parse(bhm::test::read_file(whole / "run.json"));
    CHECK(run_json.at("seed") == e.evolution.seed);
    CHECK(run_json.at("experiment").at("name") == "tiny");
    const auto champion = nlohmann::json::parse(bhm::test::read_file(whole / "champion.json"));
    CHECK(champion.at("fitness").get<double>() ==
          uninterrupted.state().champion->individual.report.fitness);
    CHECK(champion.at("phenotype").at("layers").size() == 3);
    CHECK_NOTHROW(bhm::test::XmlReader::parse(bhm::test::read_file(whole / "champion.vxa")));
    // While a run object lives it owns its directory; a new run elsewhere refuses a directory
    // that already holds a run (here a copy without the owner).
    CHECK_THROWS_AS(EvolutionRun(e, run_options(4, 1, whole.string())), RunDirectoryBusy);
    const fs::path copy = bhm::test::scratch_dir("evo-whole-copy", false);
    fs::copy(whole, copy, fs::copy_options::recursive);
    fs::remove(copy / kRunLockFile);
    CHECK_THROWS_WITH_AS(EvolutionRun(e, run_options(4, 1, copy.string())),
                         doctest::Contains("--resume"), std::runtime_error);
    fs::remove_all(copy);
    fs::remove_all(whole);
    fs::remove_all(parts);
}

TEST_CASE("a stop during a generation abandons it and leaves the state untouched") {
    const auto e = test::tiny_experiment();
    EvolutionRun run(e, run_options(3, 2));
    REQUIRE(run.run_generation());
    const auto before = run.state().history;
    const auto rng = run.state().rng;
    run.request_stop();
    CHECK_FALSE(run.run_generation());  // cancelled at the first simulation sample
    CHECK(run.state().generation == 0);
    CHECK(run.state().history == before);
    CHECK(run.state().rng == rng);
}

TEST_CASE("pause and stop reach into the simulations of a generation, resume re-runs it") {
    // Simulations long enough (0.6 s simulated) that the controls land while they run.
    auto e = test::tiny_experiment();
    e.evolution.population = 4;
    e.simulation.evaluate_s = 0.6;
    e.simulation.record_fps = 0.5;  // one sample in the window: only the in-between checks remain
    const fs::path whole = bhm::test::scratch_dir("evo-cancel-whole", false),
                   parts = bhm::test::scratch_dir("evo-cancel-parts", false);

    auto owned = std::make_unique<EvolutionRun>(e, run_options(3, 2, parts.string()));
    EvolutionRun& run = *owned;
    CHECK(run.checkpoint_path().empty());  // nothing on disk yet
    CHECK_FALSE(run.progress().running);
    StopReason reason = StopReason::GenerationBudget;
    std::thread runner([&] { reason = run.run(); });
    // Wait until generation 1 has finished some but not all of its simulations.
    GenerationProgress p;
    for (;;) {
        p = run.progress();
        if (p.running && p.generation == 1 && p.simulations_done >= 1) break;
        std::this_thread::sleep_for(std::chrono::milliseconds(1));
    }
    run.set_paused(true);
    std::this_thread::sleep_for(std::chrono::milliseconds(100));
    const GenerationProgress frozen = run.progress();
    std::this_thread::sleep_for(std::chrono::milliseconds(300));
    const GenerationProgress later = run.progress();
    REQUIRE(frozen.running);
    REQUIRE(frozen.generation == 1);
    CHECK(frozen.simulations_total >= frozen.simulations_done);
    CHECK(later.simulations_done == frozen.simulations_done);                   // paused in flight
    CHECK(later.elapsed_s == doctest::Approx(frozen.elapsed_s).epsilon(0.05));  // paused clock

    const auto asked = std::chrono::steady_clock::now();
    run.request_stop();
    runner.join();
    const double waited =
        std::chrono::duration<double>(std::chrono::steady_clock::now() - asked).count();
    CHECK(reason == StopReason::StopRequested);
    CHECK(waited < 1.0);  // each simulation alone takes longer than this under the sanitizers
    CHECK(run.state().generation == 0);     // generation 1 abandoned
    CHECK(run.progress().generation == 1);  // ... which progress still names
    CHECK_FALSE(run.progress().running);
    CHECK(run.checkpoint_path() == (parts / kCheckpointFile).string());
    CHECK(fs::exists(run.checkpoint_path()));
    CHECK(run.state().history.size() == 1);

    owned.reset();  // releases the directory
    auto resumed = EvolutionRun::resume(run_options(3, 2, parts.string()));
    CHECK(resumed->checkpoint_path() == (parts / kCheckpointFile).string());
    CHECK(resumed->run() == StopReason::GenerationBudget);
    EvolutionRun uninterrupted(e, run_options(3, 2, whole.string()));
    uninterrupted.run();
    CHECK(csv_without_wall(bhm::test::read_file(parts / "fitness.csv")) ==
          csv_without_wall(bhm::test::read_file(whole / "fitness.csv")));
    CHECK(resumed->state().rng == uninterrupted.state().rng);
    CHECK(resumed->state().champion->individual.genome ==
          uninterrupted.state().champion->individual.genome);
    const GenerationProgress done = uninterrupted.progress();
    CHECK(done.generation == 2);
    CHECK(done.simulations_done == done.simulations_total);
    CHECK(done.simulations_total == uninterrupted.state().history.back().simulations);
    fs::remove_all(whole);
    fs::remove_all(parts);
}

TEST_CASE("a corrupt checkpoint falls back to the previous one, both corrupt is a clear error") {
    const auto e = test::tiny_experiment();
    const fs::path dir = bhm::test::scratch_dir("evo-corrupt", false);
    EvolutionRun(e, run_options(2, 2, dir.string())).run();
    std::ofstream(dir / "checkpoint.json") << "{\"format\": \"bhm-evolution-checkpoint\", trunc";
    auto resumed = EvolutionRun::resume(run_options(3, 2, dir.string()));
    REQUIRE(resumed->resume_warnings().size() == 1);
    CHECK(resumed->resume_warnings()[0].find("checkpoint.json") != std::string::npos);
    CHECK(resumed->state().generation == 0);  // the previous checkpoint: after generation 0
    resumed->run();
    EvolutionRun reference(e, run_options(3, 2));
    reference.run();
    CHECK(without_wall(resumed->state().history) == without_wall(reference.state().history));
    resumed.reset();  // releases the directory

    std::ofstream(dir / "checkpoint.json") << "not json";
    std::ofstream(dir / "checkpoint.prev.json") << "{}";
    CHECK_THROWS_WITH_AS(EvolutionRun::resume(run_options(3, 2, dir.string())),
                         doctest::Contains("checkpoint.prev.json: damaged"), std::runtime_error);
    fs::remove_all(dir);
    CHECK_THROWS_WITH_AS(EvolutionRun::resume(run_options(3, 2, dir.string())),
                         doctest::Contains("no such run directory"), std::runtime_error);
}

TEST_CASE("a change of rules between generations re-scores the population and is recorded") {
    const auto e = test::tiny_experiment();
    EvolutionRun run(e, run_options(3, 2));
    REQUIRE(run.run_generation());
    Fitness rules = e.fitness;
    rules.measure = FitnessMeasure::ComFinalYz;
    rules.constraints.min_active_voxels = 6;
    run.request_fitness_change(rules);
    std::shared_ptr<const GenerationReport> report;
    run.set_report_callback([&](auto r) { report = r; });
    REQUIRE(run.run_generation());
    REQUIRE(report);
    CHECK(report->rules_changed);
    CHECK(report->rules_version == 1);
    CHECK(report->measure == FitnessMeasure::ComFinalYz);
    CHECK(run.state().history.back().rules_version == 1);
    CHECK(run.state().rule_changes.size() == 1);
    CHECK(run.state().experiment.fitness.constraints.min_active_voxels == 6);
    for (const auto& m : run.state().population) {
        if (m.valid) {
            CHECK(m.report.fitness == fitness_under(m.report, FitnessMeasure::ComFinalYz));
            CHECK(m.phenotype.active_voxels >= 6);
        } else {
            CHECK(m.report.fitness == kInvalidFitness);
            CHECK(m.phenotype.active_voxels < 6);
        }
    }
    // Applied once: the next generation runs under the same rules without another change.
    REQUIRE(run.run_generation());
    CHECK_FALSE(report->rules_changed);
    CHECK(report->rules_version == 1);
}

namespace {

//! Simulates on this process's threads; while the batch of generation `at` is in flight, asks
//! its run for a rule change (once), as the studio's Apply does.
class ChangeRulesMidBatch final : public Evaluator {
  public:
    ChangeRulesMidBatch(int at, Fitness rules) : at_(at), rules_(std::move(rules)) {}
    EvolutionRun* run = nullptr;
    bool changed = false;
    void evaluate(const EvaluationBatch& batch, std::vector<FitnessReport>& results) override {
        if (run->progress().generation == at_ && !changed && !batch.bodies.empty()) {
            changed = true;
            run->change_fitness_now(rules_);
        }
        inner_.evaluate(batch, results);
    }
    int concurrency() const override { return inner_.concurrency(); }

  private:
    int at_;
    Fitness rules_;
    ThreadEvaluator inner_{2};
};

}  // namespace

TEST_CASE(
    "run(): a rule change mid-generation restarts that generation and equals the change made "
    "between generations; a pause between generations is reported with the next generation") {
    const Experiment e = test::tiny_experiment();
    Fitness rules = e.fitness;
    rules.measure = FitnessMeasure::ComFinalYz;

    // Twin: the change requested before generation 2 starts.
    EvolutionRun twin(e, run_options(4, 2));
    twin.set_report_callback([&](auto r) {
        if (r->generation == 1) twin.request_fitness_change(rules);
    });
    REQUIRE(twin.run() == StopReason::GenerationBudget);

    // The same change made while generation 2 is being simulated: abandoned, then run again.
    auto evaluator = std::make_shared<ChangeRulesMidBatch>(2, rules);
    RunOptions o = run_options(4, 2);
    o.evaluator = evaluator;
    EvolutionRun run(e, o);
    evaluator->run = &run;
    std::vector<std::string> events;
    run.set_event_callback([&](RunEvent event, int next, bool restarted) {
        events.push_back(std::to_string(static_cast<int>(event)) + ":" + std::to_string(next) +
                         (restarted ? "r" : ""));
        if (event == RunEvent::Paused) run.set_paused(false);
    });
    run.set_report_callback([&](auto r) {
        if (r->generation == 2) run.pause_between_generations(true);
    });
    REQUIRE(run.run() == StopReason::GenerationBudget);
    REQUIRE(evaluator->changed);
    CHECK(without_wall(run.state().history) == without_wall(twin.state().history));
    REQUIRE(run.state().rule_changes.size() == 1);
    CHECK(run.state().rule_changes.front().generation == 2);
    // Restarted (2) once for generation 2, then paused (0) and resumed (1) before generation 3.
    CHECK(events == std::vector<std::string>{"2:2", "0:3", "1:3"});
}

TEST_CASE("run(): new rules that arrive while the run is held between generations do not end it") {
    const Experiment e = test::tiny_experiment();
    Fitness rules = e.fitness;
    rules.measure = FitnessMeasure::ComFinalYz;
    EvolutionRun run(e, run_options(3, 2));
    run.set_report_callback([&](auto r) {
        if (r->generation == 0) run.pause_between_generations(true);
    });
    run.set_event_callback([&](RunEvent event, int, bool) {
        if (event != RunEvent::Paused) return;
        run.change_fitness_now(rules);  // as the studio's Apply while paused
        run.set_paused(false);          // and its Resume
    });
    REQUIRE(run.run() == StopReason::GenerationBudget);
    REQUIRE(run.state().rule_changes.size() == 1);
    CHECK(run.state().rule_changes.front().generation == 1);
}
