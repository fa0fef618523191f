// NEAT on hand-built genomes: innovation numbers, gene alignment (matching, disjoint, excess), the
// compatibility distance worked out by hand, which genes a crossover child gets, acyclic children,
// speciation, fitness sharing, offspring allotment and stagnation.
#include <doctest/doctest.h>

#include <algorithm>
#include <set>

#include "evo/genome/neat_genes.hpp"
#include "evo/genome/neat_innovation.hpp"
#include "evo/search/neat_crossover.hpp"
#include "evo/search/neat_mutation.hpp"
#include "evo/search/neat_species.hpp"
#include "evo_test_support.hpp"

using namespace bhm::evo;

namespace {

// The two parents of Stanley & Miikkulainen 2002 Fig. 4, as CPPN genomes (inputs 0-4, outputs
// 5 and 6, hidden ids from 7). A holds innovations 1-5 and 8; B holds 1-5, 6, 7, 9 and 10.
// Matching: 1-5. Disjoint: 8 (A), 6 and 7 (B). Excess: 9 and 10 (B, beyond A's largest, 8).
Genome parent_a() {
    Genome g;
    g.hidden = {Activation::Sin};
    g.hidden_ids = {7};
    g.edges = {{0, 5, 0.5, 1}, {1, 5, -0.5, 2}, {2, 6, 0.25, 3},
               {0, 7, 1.0, 4}, {7, 6, 0.75, 5}, {3, 7, 0.1, 8}};
    return g;
}

Genome parent_b() {
    Genome g;
    g.hidden = {Activation::Abs, Activation::Square};
    g.hidden_ids = {7, 9};  // node id 9 sits at index 8
    g.edges = {{0, 5, -0.5, 1}, {1, 5, 0.5, 2},  {2, 6, 0.25, 3}, {0, 7, 0.0, 4}, {7, 6, 0.75, 5},
               {4, 8, 0.3, 6},  {8, 5, -0.3, 7}, {1, 7, 0.2, 9},  {8, 6, 0.6, 10}};
    return g;
}

std::set<std::int64_t> innovations(const Genome& g) {
    std::set<std::int64_t> out;
    for (const auto& e : g.edges)
        out.insert(e.innovation);
    return out;
}

const CppnEdge& gene(const Genome& g, std::int64_t innovation) {
    for (const auto& e : g.edges)
        if (e.innovation == innovation) return e;
    FAIL("no gene " << innovation);
    return g.edges.front();
}

Individual member(const Genome& g, double fitness, std::int64_t id) {
    Individual m;
    m.id = id;
    m.genome = g;
    m.report.fitness = fitness;
    m.evaluated = true;
    return m;
}

}  // namespace

TEST_CASE("innovation numbers: one per new structure in a generation, counters go on") {
    InnovationTable table(10, 20);
    const auto a = table.connection(0, 5);
    CHECK(a == 10);
    CHECK(table.connection(1, 5) == 11);
    CHECK(table.connection(0, 5) == a);  // the same mutation in another genome: the same gene
    const auto split = table.split(a, 0, 5);
    CHECK(split.node_id == 20);
    CHECK(split.in_innovation == 12);
    CHECK(split.out_innovation == 13);
    const auto again = table.split(a, 0, 5);
    CHECK(again.node_id == 20);
    CHECK(again.in_innovation == 12);
    CHECK(again.out_innovation == 13);
    table.new_generation();  // next generation: the same structure is a new innovation
    CHECK(table.connection(0, 5) == 14);
    CHECK(table.split(a, 0, 5).node_id == 21);
}

TEST_CASE("the same split in two genomes of one generation gives the same genes") {
    const auto e = test::tiny_experiment();
    Rng rng(3);
    InnovationTable table(0, kFirstHidden);
    Genome one = neat_minimal_genome(2, e.evolution.cppn, rng, table);
    Genome two = neat_minimal_genome(2, e.evolution.cppn, rng, table);
    CHECK(innovations(one) == innovations(two));  // minimal genomes all align
    CHECK(one.edges.size() == 10);
    // Down to one shared connection, so the first split of each is the same split; five more
    // random ones each then make structure that only one genome has, or both by chance.
    one.edges.resize(1);
    two.edges.resize(1);
    for (int k = 0; k < 6; ++k) {
        apply_neat_mutation(one, MutationKind::AddNode, e.evolution.cppn, rng, table);
        apply_neat_mutation(two, MutationKind::AddNode, e.evolution.cppn, rng, table);
    }
    CHECK(genome_problem(one, 1.0).empty());
    CHECK(genome_problem(two, 1.0).empty());
    // All made in one generation: the same structure (end node ids) carries the same innovation
    // number in both genomes, and the same number names the same structure.
    int shared = 0;
    for (const auto& x : one.edges)
        for (const auto& y : two.edges) {
            const bool same_ends = one.node_id(x.from) == two.node_id(y.from) &&
                                   one.node_id(x.to) == two.node_id(y.to);
            CHECK(same_ends == (x.innovation == y.innovation));
        }
    // The first split of both made the same node.
    for (auto id : one.hidden_ids)
        shared += static_cast<int>(std::count(two.hidden_ids.begin(), two.hidden_ids.end(), id));
    CHECK(shared > 0);
    CHECK(one.hidden_ids.front() == two.hidden_ids.front());
}

TEST_CASE("gene alignment and the compatibility distance of Fig. 4's parents, by hand") {
    const Genome a = parent_a(), b = parent_b();
    REQUIRE(genome_problem(a, 1.0).empty());
    REQUIRE(genome_problem(b, 1.0).empty());
    const auto al = align_genes(a, b);
    CHECK(al.matching.size() == 5);
    CHECK(al.disjoint_a.size() == 1);
    CHECK(a.edges[al.disjoint_a[0]].innovation == 8);
    CHECK(al.disjoint_b.size() == 2);
    CHECK(al.excess_a.empty());
    CHECK(al.excess_b.size() == 2);
    CHECK(b.edges[al.excess_b[0]].innovation == 9);
    CHECK(b.edges[al.excess_b[1]].innovation == 10);

    // Matching weight differences |0.5+0.5| + |-0.5-0.5| + 0 + |1-0| + 0 = 3 over 5: W-bar 0.6.
    // Both genomes hold fewer than 20 genes, so N = 1: delta = c1 2 + c2 3 + c3 0.6.
    NeatSettings s;
    CHECK(compatibility_distance(a, b, s) == doctest::Approx(2.0 + 3.0 + 0.4 * 0.6));
    s.c1 = 2.0;
    s.c2 = 0.5;
    s.c3 = 1.0;
    CHECK(compatibility_distance(a, b, s) == doctest::Approx(4.0 + 1.5 + 0.6));
    CHECK(compatibility_distance(b, a, s) == doctest::Approx(4.0 + 1.5 + 0.6));
    CHECK(compatibility_distance(a, a, s) == 0.0);

    // 20 genes or more, with normalize_by_size: E and D are divided by the larger genome's gene
    // count; without (the default), N = 1 whatever the size.
    Genome big_a = a, big_b = b;
    for (int k = 0; k < 14; ++k) {  // the same 14 extra genes in both: matching, equal weights
        big_a.edges.push_back({k % 5, 5 + k % 2, 0.1, 100 + k});
        big_b.edges.push_back({k % 5, 5 + k % 2, 0.1, 100 + k});
    }
    // Now 20 and 23 genes; innovation 100+ makes 8, 6, 7, 9 and 10 all disjoint (none is excess).
    // W-bar: 3 over 19 matching genes.
    CHECK(compatibility_distance(big_a, big_b, s) == doctest::Approx(0.5 * 5 + 1.0 * 3.0 / 19.0));
    s.normalize_by_size = true;
    CHECK(compatibility_distance(big_a, big_b, s) ==
          doctest::Approx(2.0 * 0 / 23.0 + 0.5 * 5 / 23.0 + 1.0 * 3.0 / 19.0));
    CHECK(compatibility_distance(a, b, s) == doctest::Approx(4.0 + 1.5 + 0.6));  // N = 1 below 20
}

TEST_CASE("crossover: matching genes from either parent, disjoint and excess from the fitter") {
    const Genome a = parent_a(), b = parent_b();
    std::set<double> weights_of_gene_1;
    std::set<Activation> functions_of_node_7;
    for (std::uint64_t seed = 1; seed <= 40; ++seed) {
        Rng rng(seed);
        const Genome child = neat_crossover(a, b, Fitter::Primary, rng);
        REQUIRE(genome_problem(child, 1.0).empty());
        CHECK(innovations(child) == std::set<std::int64_t>{1, 2, 3, 4, 5, 8});
        CHECK(child.hidden_ids == std::vector<std::int64_t>{7});
        for (std::int64_t i = 1; i <= 5; ++i) {
            const double w = gene(child, i).weight;
            CHECK((w == gene(a, i).weight || w == gene(b, i).weight));
        }
        CHECK(gene(child, 8).weight == 0.1);  // A's disjoint gene, A's weight
        weights_of_gene_1.insert(gene(child, 1).weight);
        functions_of_node_7.insert(child.hidden[0]);

        // The mate fitter: B's structure, B's disjoint and excess genes.
        Rng rng_b(seed);
        const Genome child_b = neat_crossover(a, b, Fitter::Mate, rng_b);
        REQUIRE(genome_problem(child_b, 1.0).empty());
        CHECK(innovations(child_b) == std::set<std::int64_t>{1, 2, 3, 4, 5, 6, 7, 9, 10});
        CHECK(child_b.hidden_ids == std::vector<std::int64_t>{7, 9});
        CHECK(child_b.hidden[1] == Activation::Square);  // node 9 is B's alone
    }
    CHECK(weights_of_gene_1 == std::set<double>{0.5, -0.5});  // both parents' weights occur
    CHECK(functions_of_node_7 == std::set<Activation>{Activation::Sin, Activation::Abs});
}

TEST_CASE("crossover of equally fit parents: unmatched genes of both, graph kept acyclic") {
    // A: 0 -> 7 -> 8 -> 5; B: 0 -> 8 -> 7 -> 6. Both hold nodes 7 and 8 but connect them in
    // opposite directions (genes 2 and 5): inheriting both would close a cycle.
    Genome a, b;
    a.hidden = b.hidden = {Activation::Sin, Activation::Abs};
    a.hidden_ids = b.hidden_ids = {7, 8};
    a.edges = {{0, 7, 0.5, 1}, {7, 8, 0.5, 2}, {8, 5, 0.5, 3}};
    b.edges = {{0, 8, 0.5, 4}, {8, 7, 0.5, 5}, {7, 6, 0.5, 6}};
    REQUIRE(genome_problem(a, 1.0).empty());
    REQUIRE(genome_problem(b, 1.0).empty());
    int with_both_sides = 0, blocked = 0;
    for (std::uint64_t seed = 1; seed <= 200; ++seed) {
        Rng rng(seed);
        const Genome child = neat_crossover(a, b, Fitter::Equal, rng);
        REQUIRE(genome_problem(child, 1.0).empty());  // acyclic, no duplicate, ids in order
        const auto got = innovations(child);
        for (auto i : got)
            CHECK(i >= 1);
        if (got.count(1) + got.count(2) + got.count(3) > 0 && got.count(4) + got.count(6) > 0)
            ++with_both_sides;
        if (got.count(2) && !got.count(5)) ++blocked;
        CHECK(!(got.count(2) && got.count(5)));
    }
    CHECK(with_both_sides > 0);  // genes of both parents are inherited
    CHECK(blocked > 0);
}

TEST_CASE("random NEAT genomes crossed at random stay well formed") {
    const auto e = test::tiny_experiment();
    Rng rng(11);
    InnovationTable table(0, kFirstHidden);
    std::vector<Genome> pool;
    for (int i = 0; i < 12; ++i)
        pool.push_back(neat_minimal_genome(2, e.evolution.cppn, rng, table));
    for (int round = 0; round < 300; ++round) {
        if (round % 12 == 0) table.new_generation();
        auto& g = pool[static_cast<std::size_t>(rng.index(12))];
        apply_neat_mutation(g, random_mutation_kind(rng), e.evolution.cppn, rng, table);
        const auto& x = pool[static_cast<std::size_t>(rng.index(12))];
        const auto& y = pool[static_cast<std::size_t>(rng.index(12))];
        const auto fitter = static_cast<Fitter>(rng.index(3));
        const Genome child = neat_crossover(x, y, fitter, rng);
        REQUIRE(genome_problem(child, 1.0).empty());
        REQUIRE(genome_problem(g, 1.0).empty());
    }
}

TEST_CASE("speciation by threshold, fitness sharing, offspring per species and stagnation") {
    const Genome a = parent_a(), b = parent_b();
    Genome a2 = a;
    a2.edges[0].weight = 0.3;  // delta(a, a2) = 0.4 * 0.2 / 6
    std::vector<Individual> population = {member(a, 3.0, 1), member(b, 2.0, 2), member(a2, 1.0, 3)};
    NeatSettings s;  // threshold 3: delta(a, b) = 5.24 apart, a and a2 together
    s.target_species = 0;  // a fixed threshold until said otherwise below
    NeatState state;
    state.threshold = s.compatibility_threshold;
    speciate(population, s, 0, state);
    REQUIRE(state.species.size() == 2);
    CHECK(state.species[0].members == std::vector<int>{0, 2});  // best first
    CHECK(state.species[1].members == std::vector<int>{1});
    CHECK(state.species[0].id == 1);
    CHECK(state.species[1].id == 2);
    CHECK(state.species[0].best_fitness == 3.0);
    CHECK(species_of_members(state, 3) == std::vector<int>{0, 1, 0});

    // Shifted by the lowest fitness (1): 2, 1, 0; divided by species sizes 2, 1, 2.
    const auto adjusted = adjusted_fitness(population, state);
    CHECK(adjusted == std::vector<double>{1.0, 1.0, 0.0});
    // Species sums 1 and 1: 10 offspring split 5 and 5; 9 split 5 and 4 (the older wins ties).
    CHECK(allot_offspring(population, state, s, 1, 10) == std::vector<int>{5, 5});
    CHECK(allot_offspring(population, state, s, 1, 9) == std::vector<int>{5, 4});

    // The second species has not improved for stagnation_generations: it breeds no more. The
    // first holds the best member, so it is never retired, however old its record.
    state.species[1].last_improved = 0;
    state.species[0].last_improved = 0;
    CHECK(allot_offspring(population, state, s, 1 + s.stagnation_generations, 10) ==
          std::vector<int>{10, 0});

    // The best member's species always breeds: here its mean is low (a2 scores -2, shifting a to
    // 5, a2 to 0, b to 4: shares 2.5 and 4) and one offspring would go to b's species.
    state.species[0].last_improved = state.species[1].last_improved = 0;
    population[2].report.fitness = -2.0;
    CHECK(adjusted_fitness(population, state) == std::vector<double>{2.5, 4.0, 0.0});
    CHECK(allot_offspring(population, state, s, 1, 1) == std::vector<int>{1, 0});
    CHECK(allot_offspring(population, state, s, 1, 3) == std::vector<int>{1, 2});

    // Everyone equally fit: shares by species size.
    for (auto& m : population)
        m.report.fitness = 1.0;
    CHECK(allot_offspring(population, state, s, 1, 9) == std::vector<int>{6, 3});

    // A change of fitness rules: records restart from the re-scored members, best first again.
    population[2].report.fitness = 4.0;  // a2 now beats a
    restart_species_records(population, 7, state);
    CHECK(state.species[0].members == std::vector<int>{2, 0});
    CHECK(state.species[0].best_fitness == 4.0);
    CHECK(state.species[0].last_improved == 7);
    population[2].report.fitness = 1.0;

    // A target of one species raises the threshold by one step after a speciation with two.
    s.target_species = 1;
    const double before = state.threshold;
    speciate(population, s, 1, state);
    CHECK(state.species.size() == 2);
    CHECK(state.threshold == doctest::Approx(before + s.threshold_step));
    // The representatives are the species' best members: a (or a2, now equally fit: id 1 first).
    CHECK(state.species[0].representative == a);
}
