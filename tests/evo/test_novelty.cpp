// Novelty search's parts: k-nearest novelty worked out by hand (archive included), the archive's
// rule, AFPO with a second objective, novelty selection on hand-built members, and the
// experiment fields' validation.
#include <doctest/doctest.h>

#include <cmath>

#include "evo/evaluate/behaviour.hpp"
#include "evo/experiment/experiment_io.hpp"
#include "evo/search/afpo.hpp"
#include "evo/search/novelty.hpp"
#include "evo/search/novelty_archive.hpp"
#include "evo/search/novelty_selection.hpp"
#include "evo_test_support.hpp"

using namespace bhm::evo;

TEST_CASE("novelty is the mean distance to the k nearest of the others and the archive") {
    // Pool A = (0, 0), B = (3, 0), C = (0, 4), D without a descriptor; archive E = (6, 8).
    // |AB| = 3, |AC| = 4, |BC| = 5, |AE| = 10, |BE| = sqrt(73), |CE| = sqrt(52).
    const BehaviourDescriptor a{0, 0}, b{3, 0}, c{0, 4};
    const std::deque<BehaviourDescriptor> archive{{6, 8}};
    const std::vector<const BehaviourDescriptor*> pool{&a, &b, &c, nullptr};
    CHECK(behaviour_distance(b, c) == 5.0);

    auto k2 = novelty_scores(pool, archive, 2);
    CHECK(k2[0] == doctest::Approx(3.5));  // (3 + 4) / 2
    CHECK(k2[1] == doctest::Approx(4.0));  // (3 + 5) / 2
    CHECK(k2[2] == doctest::Approx(4.5));  // (4 + 5) / 2
    CHECK(k2[3] == kNoNovelty);            // and D is nobody's neighbour

    auto k3 = novelty_scores(pool, archive, 3);
    CHECK(k3[0] == doctest::Approx(17.0 / 3.0));
    CHECK(k3[1] == doctest::Approx((3.0 + 5.0 + std::sqrt(73.0)) / 3.0));
    CHECK(k3[2] == doctest::Approx((4.0 + 5.0 + std::sqrt(52.0)) / 3.0));
    // k beyond the neighbours available: the mean of all of them.
    CHECK(novelty_scores(pool, archive, 50)[0] == doctest::Approx(17.0 / 3.0));

    // An archive entry near A makes A less novel: its nearest are now 0.5 and 3.
    const std::deque<BehaviourDescriptor> near_a{{0, 0.5}};
    CHECK(novelty_scores(pool, near_a, 2)[0] == doctest::Approx(1.75));
    // Without the archive A's k = 3 neighbours are only B and C.
    CHECK(novelty_scores(pool, {}, 3)[0] == doctest::Approx(3.5));

    // Alone, with an empty archive: nothing to differ from.
    CHECK(novelty_scores({&a}, {}, 15)[0] == 0.0);
    // A twin is a neighbour at distance 0.
    const BehaviourDescriptor a2 = a;
    CHECK(novelty_scores({&a, &a2, &b}, {}, 1)[0] == 0.0);
}

TEST_CASE("the archive takes new behaviours above its adaptive threshold, oldest out first") {
    const BehaviourDescriptor p{1}, q{2}, r{3}, s{4}, t{5};
    NoveltyArchive archive;
    archive.threshold = 2.0;
    // Strictly above 2 and with a descriptor: only r.
    CHECK(update_archive(archive, {&p, &q, &r, nullptr}, {1.0, 2.0, 3.0, 5.0}, 10) == 1);
    REQUIRE(archive.entries.size() == 1);
    CHECK(archive.entries[0] == r);
    CHECK(archive.threshold == 2.0);  // one entry: neither busy nor idle

    CHECK(update_archive(archive, {&p}, {1.0}, 10) == 0);  // idle: lowered 5 %
    CHECK(archive.threshold == doctest::Approx(2.0 * kThresholdLower));

    archive.threshold = 1.0;  // five entries: busy, raised 20 %; capacity 3 keeps the newest
    CHECK(update_archive(archive, {&p, &q, &r, &s, &t}, {2, 2, 2, 2, 2}, 3) == 5);
    CHECK(archive.threshold == doctest::Approx(kThresholdRaise));
    REQUIRE(archive.entries.size() == 3);
    CHECK(archive.entries[0] == r);
    CHECK(archive.entries[2] == t);

    CHECK(update_archive(archive, {&p}, {100.0}, 0) == 1);  // capacity 0: no archive at all
    CHECK(archive.entries.empty());
}

TEST_CASE("AFPO's second objective takes part in dominance and in the tie order") {
    const AfpoObjectives a{1.0, 2, 0, 1, 5.0}, b{1.0, 2, 0, 2, 3.0};
    CHECK_FALSE(dominates(a, b, AfpoOptions{false, false}));  // equal without the second
    CHECK(dominates(a, b, AfpoOptions{false, true}));
    CHECK_FALSE(dominates(b, a, AfpoOptions{false, true}));
    // The old two-objective overloads are unchanged.
    CHECK(pareto_ranks({a, b}, false) == std::vector<int>{0, 0});
    CHECK(pareto_ranks({a, b}, AfpoOptions{false, true}) == std::vector<int>{0, 1});
    // In an overflowing layer, the second objective orders before age.
    const AfpoObjectives c{1.0, 3, 0, 0, 9.0};  // older, but better in the second
    CHECK(select_survivors({a, c}, 1, AfpoOptions{false, true}) == std::vector<int>{1});
    CHECK(select_survivors({a, c}, 1, AfpoOptions{false, false}) == std::vector<int>{0});
}

namespace {

Individual member(std::int64_t id, double x, double fitness) {
    Individual m;
    m.id = id;
    m.evaluated = true;
    m.report.fitness = fitness;
    m.report.behaviour.assign(kBehaviourLength, 0.0);
    m.report.behaviour[0] = x;
    return m;
}

}  // namespace

TEST_CASE("novelty selection: the most novel survive, fitness breaks novelty ties when asked") {
    auto rules = test::tiny_experiment();
    rules.evolution.population = 2;
    rules.evolution.novelty.k = 1;
    // B (id 1) and A (id 2) at 1 and 0: novelty 1 each; C at 10: novelty 9. A is the fittest.
    std::vector<Individual> pool{member(1, 1.0, 1.0), member(2, 0.0, 5.0), member(3, 10.0, 0.0)};
    NoveltyArchive archive;
    archive.threshold = 0.5;

    auto pure = select_by_novelty(pool, 1, archive, rules);
    CHECK(pure.novelty == std::vector<double>{1.0, 1.0, 9.0});
    // C dominates both; A and B tie on (novelty, age) and the id decides.
    CHECK(pure.survivors == std::vector<int>{2, 0});
    CHECK(pure.ranks == std::vector<int>{1, 1, 0});
    // The new ones (A and C, pool[1..]) are above 0.5: both enter, oldest first.
    CHECK(pure.added == 2);
    REQUIRE(pure.archive.entries.size() == 2);
    CHECK(pure.archive.entries[0][0] == 0.0);
    CHECK(pure.archive.entries[1][0] == 10.0);

    rules.evolution.novelty.with_fitness = true;
    auto with_fitness = select_by_novelty(pool, 1, archive, rules);
    // Now A dominates B (same novelty, fitter): C and A form the front.
    CHECK(with_fitness.ranks == std::vector<int>{1, 0, 0});
    CHECK(with_fitness.survivors == std::vector<int>{2, 1});

    // Members without a usable descriptor score kNoNovelty and never enter the archive.
    pool[2].valid = false;
    pool[1].report.diverged = true;
    auto broken = select_by_novelty(pool, 1, archive, rules);
    CHECK(broken.novelty == std::vector<double>{0.0, kNoNovelty, kNoNovelty});
    CHECK(broken.added == 0);
}

TEST_CASE("evolution.novelty fields: defaults, round trip, one-line errors naming file and field") {
    const std::string demo = std::string(BHM_SOURCE_DIR) + "/assets/experiments/quick-demo.json";
    auto base = experiment_to_json(load_experiment(demo));
    const auto defaults = parse_experiment(base, "demo.json").evolution.novelty;
    CHECK(defaults == NoveltySettings{});
    CHECK(defaults.k == 15);
    CHECK_FALSE(defaults.with_fitness);

    auto j = base;
    j["evolution"]["novelty"] = {
        {"k", 7}, {"archive_threshold", 0.25}, {"archive_capacity", 40}, {"with_fitness", true}};
    const auto e = parse_experiment(j, "demo.json");
    CHECK(e.evolution.novelty == NoveltySettings{7, 0.25, 40, true});
    CHECK(parse_experiment(experiment_to_json(e), "again.json") == e);

    auto problem = [&](const char* key, nlohmann::json value) {
        auto bad = base;
        bad["evolution"]["novelty"][key] = value;
        try {
            parse_experiment(bad, "bad.json");
        } catch (const ValidationError& error) {
            REQUIRE(error.problems.size() == 1);
            return error.problems[0].to_string();
        }
        return std::string("accepted");
    };
    CHECK(problem("k", 0).rfind("bad.json:evolution.novelty.k: must be in [1, 1000]", 0) == 0);
    CHECK(problem("k", 1001).rfind("bad.json:evolution.novelty.k:", 0) == 0);
    CHECK(problem("k", 2.5).rfind("bad.json:evolution.novelty.k:", 0) == 0);
    CHECK(problem("archive_threshold", 0.0)
              .rfind("bad.json:evolution.novelty.archive_threshold: must be in (0, 1e6]", 0) == 0);
    CHECK(problem("archive_threshold", "one")
              .rfind("bad.json:evolution.novelty.archive_threshold:", 0) == 0);
    CHECK(problem("archive_capacity", -1)
              .rfind("bad.json:evolution.novelty.archive_capacity: must be in [0, 100000]", 0) ==
          0);
    CHECK(problem("with_fitness", 1).rfind("bad.json:evolution.novelty.with_fitness:", 0) == 0);
    const auto typo = problem("kk", 3);
    CHECK(typo.rfind("bad.json:evolution.novelty.kk:", 0) == 0);
    CHECK(typo.find("did you mean 'k'") != std::string::npos);
    CHECK(problem("archive_capacity", 0) == "accepted");  // no archive is a valid choice
}
