// CPPN genomes: activation functions, graph order, random construction and the JSON form.
#include <doctest/doctest.h>

#include <cmath>

#include "evo/genome/genome.hpp"

using namespace bhm::evo;

TEST_CASE("hidden-node functions are the seven of paper Table 2") {
    CHECK(activate(Activation::Sin, 0.5) == doctest::Approx(std::sin(0.5)));
    CHECK(activate(Activation::Abs, -0.3) == doctest::Approx(0.3));
    CHECK(activate(Activation::NegAbs, -0.3) == doctest::Approx(-0.3));
    CHECK(activate(Activation::Square, -0.5) == doctest::Approx(0.25));
    CHECK(activate(Activation::NegSquare, -0.5) == doctest::Approx(-0.25));
    CHECK(activate(Activation::SqrtAbs, -0.25) == doctest::Approx(0.5));
    CHECK(activate(Activation::NegSqrtAbs, 0.25) == doctest::Approx(-0.5));
}

TEST_CASE("topological order puts every edge forward and rejects cycles") {
    Genome g;
    g.hidden = {Activation::Sin, Activation::Abs};
    // x -> h8 -> h7 -> material: h8 must come before h7 although its index is larger.
    g.edges = {{kInputX, 8, 1.0}, {8, 7, 1.0}, {7, kOutputMaterial, 1.0}};
    const auto order = topological_order(g);
    REQUIRE(order.size() == 9);
    std::vector<int> position(9);
    for (int i = 0; i < 9; ++i)
        position[order[i]] = i;
    for (const auto& e : g.edges)
        CHECK(position[e.from] < position[e.to]);
    CHECK(genome_problem(g, 1.0).empty());

    CHECK_FALSE(edge_keeps_acyclic(g, 7, 8));  // 8 -> 7 exists: 7 -> 8 would close a loop
    CHECK(edge_keeps_acyclic(g, 8, kOutputActive));
    g.edges.push_back({7, 8, 0.5});
    CHECK_THROWS_AS(topological_order(g), std::invalid_argument);
    CHECK(genome_problem(g, 1.0).find("cycle") != std::string::npos);
}

TEST_CASE("genome_problem names malformed graphs") {
    Genome g;
    g.hidden = {Activation::Sin};
    g.edges = {{kOutputMaterial, 7, 0.1}};
    CHECK(genome_problem(g, 1.0).find("leaves an output") != std::string::npos);
    g.edges = {{7, kInputX, 0.1}};
    CHECK(genome_problem(g, 1.0).find("enters an input") != std::string::npos);
    g.edges = {{kInputX, 7, 1.5}};
    CHECK(genome_problem(g, 1.0).find("weight") != std::string::npos);
    g.edges = {{kInputX, 7, 0.5}, {kInputX, 7, 0.2}};
    CHECK(genome_problem(g, 1.0).find("duplicate") != std::string::npos);
    g.edges = {{kInputX, 9, 0.5}};
    CHECK(genome_problem(g, 1.0).find("out of range") != std::string::npos);
}

TEST_CASE("random genomes: 4-10 hidden nodes, acyclic, weights in range, every hidden node used") {
    CppnSettings settings;  // Table 2 defaults
    Rng rng(42);
    int smallest = 100, largest = 0;
    for (int trial = 0; trial < 500; ++trial) {
        const Genome g = random_genome(settings, rng);
        CAPTURE(trial);
        REQUIRE(genome_problem(g, settings.weight_range).empty());
        smallest = std::min(smallest, g.hidden_count());
        largest = std::max(largest, g.hidden_count());
        for (int h = kFirstHidden; h < g.node_count(); ++h) {
            bool consumed = false, fed = false;
            for (const auto& e : g.edges) {
                consumed |= e.from == h;
                fed |= e.to == h;
            }
            CHECK(consumed);
            CHECK(fed);
        }
    }
    CHECK(smallest == 4);
    CHECK(largest == 10);
}

TEST_CASE("the same seed gives the same genome") {
    CppnSettings settings;
    Rng a(9), b(9);
    CHECK(random_genome(settings, a) == random_genome(settings, b));
    CHECK(random_genome(settings, a) != random_genome(settings, a));
}

TEST_CASE("genome JSON round trip is exact and malformed JSON names the field") {
    CppnSettings settings;
    Rng rng(3);
    const Genome g = random_genome(settings, rng);
    const auto json = nlohmann::json::parse(genome_to_json(g).dump());
    CHECK(genome_from_json(json, 1.0) == g);

    auto bad = genome_to_json(g);
    bad["hidden"][0] = "tanh";
    CHECK_THROWS_WITH_AS(genome_from_json(bad, 1.0), doctest::Contains("genome.hidden[0]"),
                         std::invalid_argument);
    bad = genome_to_json(g);
    bad["edges"][0] = {1, 2};
    CHECK_THROWS_WITH_AS(genome_from_json(bad, 1.0), doctest::Contains("genome.edges[0]"),
                         std::invalid_argument);
}

TEST_CASE("rng: uniform_int covers its inclusive range without bias, normal has unit variance") {
    Rng rng(1);
    std::array<int, 7> counts{};
    for (int i = 0; i < 70000; ++i)
        ++counts[static_cast<std::size_t>(rng.uniform_int(0, 6))];
    for (int c : counts)
        CHECK(c == doctest::Approx(10000).epsilon(0.05));
    double sum = 0, sum2 = 0;
    const int n = 100000;
    for (int i = 0; i < n; ++i) {
        const double x = rng.normal();
        sum += x;
        sum2 += x * x;
    }
    CHECK(sum / n == doctest::Approx(0.0).epsilon(0.02));
    CHECK(sum2 / n == doctest::Approx(1.0).epsilon(0.02));
    // The state is the whole story: restoring it replays the stream.
    const auto saved = rng.state();
    const auto first = rng.next_u64();
    rng.set_state(saved);
    CHECK(rng.next_u64() == first);
}
