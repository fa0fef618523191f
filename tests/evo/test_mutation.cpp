// Mutation operators keep genomes well formed; the neutral retry always changes the phenotype.
#include <doctest/doctest.h>

#include "evo/evaluate/constraints.hpp"
#include "evo/search/mutation.hpp"
#include "evo_test_support.hpp"

using namespace bhm::evo;

TEST_CASE("property: thousands of random mutations keep the graph acyclic and weights in range") {
    CppnSettings settings;
    settings.weight_range = 0.8;  // tighter than 1 so clipping of split and perturbed edges shows
    settings.mutation_weight_sigma = 2.0;
    Rng rng(2024);
    std::array<int, kMutationKindCount> applied{};
    for (int lineage = 0; lineage < 20; ++lineage) {
        Genome g = random_genome(settings, rng);
        for (int step = 0; step < 200; ++step) {
            const auto kind = random_mutation_kind(rng);
            const Genome before = g;
            const bool changed = apply_mutation(g, kind, settings, rng);
            CAPTURE(lineage);
            CAPTURE(step);
            CAPTURE(kMutationNames[static_cast<int>(kind)]);
            REQUIRE(genome_problem(g, settings.weight_range) == "");
            if (changed) {
                ++applied[static_cast<std::size_t>(kind)];
            } else {
                CHECK(g == before);  // a mutation that cannot apply leaves the genome alone
            }
        }
    }
    for (int k = 0; k < kMutationKindCount; ++k) {
        CAPTURE(kMutationNames[k]);
        CHECK(applied[static_cast<std::size_t>(k)] > 300);  // ~4000 / 6 drawn each
    }
}

TEST_CASE("each operator does what its name says") {
    CppnSettings settings;
    Rng rng(5);
    Genome g;
    g.hidden = {Activation::Sin};
    g.edges = {{kInputX, 7, 0.5}, {7, kOutputMaterial, -0.25}};

    Genome a = g;
    REQUIRE(apply_mutation(a, MutationKind::AddNode, settings, rng));
    CHECK(a.hidden_count() == 2);
    CHECK(a.edges.size() == 3);  // one edge split into two
    CHECK(genome_problem(a, 1.0).empty());

    Genome m = g;
    REQUIRE(apply_mutation(m, MutationKind::ModifyNode, settings, rng));
    CHECK(m.hidden[0] != Activation::Sin);

    Genome r = g;
    REQUIRE(apply_mutation(r, MutationKind::RemoveNode, settings, rng));
    CHECK(r.hidden.empty());
    CHECK(r.edges.empty());

    Genome e = g;
    REQUIRE(apply_mutation(e, MutationKind::AddEdge, settings, rng));
    CHECK(e.edges.size() == 3);

    Genome w = g;
    REQUIRE(apply_mutation(w, MutationKind::ModifyEdge, settings, rng));
    CHECK(w.edges.size() == 2);
    CHECK((w.edges[0].weight != 0.5 || w.edges[1].weight != -0.25));

    Genome d = g;
    REQUIRE(apply_mutation(d, MutationKind::RemoveEdge, settings, rng));
    CHECK(d.edges.size() == 1);

    Genome bare;  // nothing to act on
    CHECK_FALSE(apply_mutation(bare, MutationKind::RemoveNode, settings, rng));
    CHECK_FALSE(apply_mutation(bare, MutationKind::RemoveEdge, settings, rng));
    CHECK_FALSE(apply_mutation(bare, MutationKind::AddNode, settings, rng));
    CHECK(bare == Genome{});
}

TEST_CASE("removing a hidden node renumbers the later ones") {
    Genome g;
    g.hidden = {Activation::Sin, Activation::Abs, Activation::Square};
    g.edges = {{kInputX, 7, 0.1}, {kInputY, 8, 0.2}, {8, 9, 0.3}, {9, kOutputMaterial, 0.4}};
    // Remove node 7 (the only choice with this seed is irrelevant: test every index).
    for (std::uint64_t seed = 1; seed < 40; ++seed) {
        Genome r = g;
        Rng rng(seed);
        REQUIRE(apply_mutation(r, MutationKind::RemoveNode, CppnSettings{}, rng));
        CHECK(genome_problem(r, 1.0).empty());
        CHECK(r.hidden_count() == 2);
    }
    Genome r = g;
    r.hidden.erase(r.hidden.begin());
    // Expected result when node 7 goes: 8 -> 7, 9 -> 8.
    const std::vector<CppnEdge> expected = {
        {kInputY, 7, 0.2}, {7, 8, 0.3}, {8, kOutputMaterial, 0.4}};
    bool seen = false;
    for (std::uint64_t seed = 1; seed < 40 && !seen; ++seed) {
        Genome t = g;
        Rng rng(seed);
        apply_mutation(t, MutationKind::RemoveNode, CppnSettings{}, rng);
        seen = t.hidden == r.hidden && t.edges == expected;
    }
    CHECK(seen);
}

TEST_CASE("neutral retry: the child's phenotype differs from the parent's and is valid") {
    const auto e = test::tiny_experiment({5, 4, 3});
    const Developer dev(e);
    Rng rng(11);
    Genome parent;
    do
        parent = random_genome(e.evolution.cppn, rng);
    while (
        !constraint_violation(e.fitness.constraints, e.boundary, dev.space(), dev.develop(parent))
             .empty());
    const Phenotype parent_phenotype = dev.develop(parent);
    int retried = 0;
    for (int i = 0; i < 30; ++i) {
        const auto out = mutate_until_new(parent, parent_phenotype, dev, e.fitness.constraints,
                                          e.evolution.cppn, 1500, rng);
        CHECK_FALSE(out.cloned);
        CHECK(out.phenotype.body.cells != parent_phenotype.body.cells);
        CHECK(out.phenotype == dev.develop(out.genome));
        CHECK(constraint_violation(e.fitness.constraints, e.boundary, dev.space(), out.phenotype)
                  .empty());
        retried += out.attempts > 1 ? 1 : 0;
    }
    CHECK(retried > 0);  // some first mutations were neutral or invalid and were redrawn

    // Constraints nothing can meet: after max_retries the child is a clone of the parent.
    auto impossible = e.fitness.constraints;
    impossible.min_active_voxels = 1000;
    const auto clone =
        mutate_until_new(parent, parent_phenotype, dev, impossible, e.evolution.cppn, 25, rng);
    CHECK(clone.cloned);
    CHECK(clone.attempts == 25);
    CHECK(clone.genome == parent);
    CHECK(clone.phenotype == parent_phenotype);
}
