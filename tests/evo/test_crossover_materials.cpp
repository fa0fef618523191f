// AFPO crossover (evo/search/crossover.hpp): aligned genes, acyclic children, deterministic runs; more
// than two materials (per-material CPPN outputs): a 3-material body decoded as worked out by hand.
#include <doctest/doctest.h>

#include "evo/experiment/experiment_io.hpp"
#include "evo/genome/cppn_decoder.hpp"
#include "evo/genome/phenotype.hpp"
#include "evo/run/evolution_run.hpp"
#include "evo/search/crossover.hpp"
#include "evo/search/mutation.hpp"
#include "evo_test_support.hpp"

using namespace bhm::evo;

namespace {

Experiment three_material_experiment() {
    auto e = test::tiny_experiment({4, 3, 3});
    MaterialEntry stiff;
    stiff.name = "stiff passive";
    stiff.physics.youngs_modulus_pa = 5e7;
    e.materials.push_back(stiff);  // 1 passive, 2 active, 3 stiff passive
    e.evolution.cppn.material_outputs = MaterialOutputs::PerMaterial;
    return e;
}

}  // namespace

TEST_CASE("crossover keeps genes both parents share and never closes a cycle") {
    // Primary: x -> h7 -> h8 -> material; mate: x -> h8 -> h7 -> active. A plain union of the
    // two would hold both 7 -> 8 and 8 -> 7, a cycle.
    Genome primary, mate;
    primary.hidden = {Activation::Sin, Activation::Abs};
    primary.edges = {{kInputX, 7, 0.5}, {7, 8, 0.25}, {8, kOutputMaterial, 1.0}};
    mate.hidden = {Activation::Square, Activation::NegAbs};
    mate.edges = {{kInputX, 7, -0.5}, {8, 7, 0.75}, {7, kOutputActive, 1.0}, {kInputY, 8, 0.1}};
    for (std::uint64_t seed = 1; seed <= 200; ++seed) {
        Rng rng(seed);
        const Genome child = crossover(primary, mate, rng);
        REQUIRE(genome_problem(child, 1.0).empty());
        CHECK_FALSE((has_edge(child, 7, 8) && has_edge(child, 8, 7)));
        // The aligned gene x -> 7 is in both parents: always kept, with either parent's weight.
        REQUIRE(has_edge(child, kInputX, 7));
        for (const auto& e : child.edges)
            if (e.from == kInputX && e.to == 7) CHECK((e.weight == 0.5 || e.weight == -0.5));
        // Hidden functions come from the parent at the same position.
        CHECK((child.hidden[0] == Activation::Sin || child.hidden[0] == Activation::Square));
        CHECK((child.hidden[1] == Activation::Abs || child.hidden[1] == Activation::NegAbs));
        CHECK(child.hidden_count() == primary.hidden_count());
    }
}

TEST_CASE("crossover of random, mutated genomes is always a well-formed acyclic genome") {
    CppnSettings settings;
    Rng rng(11);
    for (int trial = 0; trial < 300; ++trial) {
        Genome a = random_genome(settings, rng), b = random_genome(settings, rng);
        for (int k = 0; k < 5; ++k) {
            apply_mutation(a, random_mutation_kind(rng), settings, rng);
            apply_mutation(b, random_mutation_kind(rng), settings, rng);
        }
        const Genome child = crossover(a, b, rng);
        REQUIRE(genome_problem(child, settings.weight_range).empty());
        CHECK_NOTHROW(topological_order(child));
    }
}

TEST_CASE("a 3-material CPPN decodes as worked out by hand") {
    // Outputs: presence = bias (every cell filled); material 1 = x, material 2 = -x,
    // material 3 = 0.5 (bias). On x = -1, 0, 1: (-1, 1, .5) -> 2, (0, 0, .5) -> 3, (1, -1, .5)
    // -> 1.
    const int presence = kInputCount, m1 = kInputCount + 1, m2 = kInputCount + 2,
              m3 = kInputCount + 3;
    Genome g;
    g.output_count = 4;
    g.edges = {{kInputBias, presence, 1.0},
               {kInputX, m1, 1.0},
               {kInputX, m2, -1.0},
               {kInputBias, m3, 0.5}};
    REQUIRE(genome_problem(g, 1.0).empty());
    CppnDecoder decoder({3, 1, 1}, CppnMaterials{0, 0, {1, 2, 3}});
    const Body body = decoder.decode(g);
    CHECK(body.cells == std::vector<std::uint8_t>{2, 3, 1});
    // Without material 2's edge: (-1, 0, .5) -> 3, (0, 0, .5) -> 3, (1, 0, .5) -> 1.
    g.edges.erase(g.edges.begin() + 2);
    CHECK(decoder.decode(g).cells == std::vector<std::uint8_t>{3, 3, 1});
    // Ties go to the first material: presence alone leaves every material output at 0.
    g.edges = {{kInputBias, presence, 1.0}};
    CHECK(decoder.decode(g).cells == std::vector<std::uint8_t>{1, 1, 1});
    // A two-output genome does not fit a per-material decoder.
    Genome classic;
    CHECK_THROWS_AS(decoder.decode(classic), std::invalid_argument);
}

TEST_CASE("per-material experiments evolve bodies with every material, files round-trip") {
    const auto e = three_material_experiment();
    const auto again = parse_experiment(experiment_to_json(e), "test");
    CHECK(again == e);
    const Developer developer(e);
    CHECK(developer.cppn_output_count() == 4);
    Rng rng(3);
    std::array<int, 4> seen{};
    for (int k = 0; k < 200; ++k) {
        const Genome g = random_genome(e.evolution.cppn, rng, developer.cppn_output_count());
        REQUIRE(genome_from_json(genome_to_json(g), 1.0) == g);
        for (auto c : developer.develop(g).body.cells)
            ++seen[c];
    }
    CHECK(seen[1] > 0);
    CHECK(seen[2] > 0);
    CHECK(seen[3] > 0);

    auto bad = e;
    bad.evolution.crossover_rate = 1.5;
    CHECK_FALSE(validate_experiment(bad, "x").empty());
}

TEST_CASE("the multi-material preset loads and holds three materials for per-material outputs") {
    const auto e = load_experiment(BHM_SOURCE_DIR "/assets/experiments/multi-material.json");
    CHECK(e.materials.size() >= 3);
    CHECK(e.evolution.cppn.material_outputs == MaterialOutputs::PerMaterial);
    CHECK(Developer(e).cppn_output_count() == 1 + static_cast<int>(e.materials.size()));
}

TEST_CASE("AFPO with crossover: the same seed gives the same run with 1 and 2 threads") {
    auto e = three_material_experiment();
    e.evolution.crossover_rate = 0.5;
    auto history = [&](int threads) {
        RunOptions o;
        o.generations = 3;
        o.threads = threads;
        EvolutionRun run(e, o);
        run.run();
        auto rows = run.state().history;
        for (auto& r : rows)
            r.wall_s = 0.0;
        return std::make_pair(rows, run.state().champion->individual.genome);
    };
    const auto one = history(1), two = history(2);
    CHECK(one.first == two.first);
    CHECK(one.second == two.second);
}
