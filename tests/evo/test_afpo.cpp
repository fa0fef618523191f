// AFPO selection (Schmidt & Lipson 2010): domination, Pareto layers, the deterministic cut.
#include <doctest/doctest.h>

#include <algorithm>

#include "evo/genome/rng.hpp"
#include "evo/search/afpo.hpp"

using namespace bhm::evo;

TEST_CASE("domination on fitness (up) and age (down), optionally active voxels (down)") {
    const AfpoObjectives a{2.0, 1, 10, 0}, b{1.0, 3, 5, 1}, c{2.0, 1, 10, 2}, d{2.0, 0, 10, 3};
    CHECK(dominates(a, b, false));  // fitter and younger
    CHECK_FALSE(dominates(b, a, false));
    CHECK_FALSE(dominates(a, c, false));  // identical objectives: neither dominates
    CHECK_FALSE(dominates(c, a, false));
    CHECK(dominates(d, a, false));       // same fitness, younger
    CHECK_FALSE(dominates(a, b, true));  // b has fewer active voxels: a no longer dominates it
    const AfpoObjectives lean{2.0, 1, 4, 4};
    CHECK(dominates(lean, a, true));
    CHECK_FALSE(dominates(lean, a, false));  // only the third objective differs
}

TEST_CASE("Pareto layers of a small pool") {
    // (fitness, age): A(5,3) B(4,1) C(3,0) D(4,3) E(2,2) F(1,5)
    const std::vector<AfpoObjectives> pool = {{5, 3, 0, 0}, {4, 1, 0, 1}, {3, 0, 0, 2},
                                              {4, 3, 0, 3}, {2, 2, 0, 4}, {1, 5, 0, 5}};
    const auto rank = pareto_ranks(pool, false);
    CHECK(rank == std::vector<int>{0, 0, 0, 1, 1, 2});
    // Take 4: layer 0 (A, B, C) whole, then the best of layer 1 by fitness: D (4) before E (2).
    CHECK(select_survivors(pool, 4, false) == std::vector<int>{0, 1, 2, 3});
    // Take 2: layer 0 overflows; fitness desc keeps A then B.
    CHECK(select_survivors(pool, 2, false) == std::vector<int>{0, 1});
}

TEST_CASE("ties in the overflowing layer: fitness desc, then age asc, then id asc") {
    const std::vector<AfpoObjectives> pool = {{1, 2, 0, 9}, {1, 2, 0, 4}, {1, 2, 0, 7}};
    CHECK(select_survivors(pool, 2, false) == std::vector<int>{1, 2});
}

TEST_CASE("a 2P+1 = 101 pool is cut to P = 50, the best and the newcomer survive") {
    Rng rng(77);
    std::vector<AfpoObjectives> pool;
    for (int i = 0; i < 101; ++i)
        pool.push_back({rng.uniform(0.0, 10.0), 1 + rng.index(30), rng.index(50), i});
    pool[100].age = 0;  // the random newcomer
    pool[100].fitness = 0.01;
    const auto survivors = select_survivors(pool, 50, false);
    CHECK(survivors.size() == 50);
    std::vector<int> sorted = survivors;
    std::sort(sorted.begin(), sorted.end());
    CHECK(std::adjacent_find(sorted.begin(), sorted.end()) == sorted.end());  // no duplicates
    const int best =
        static_cast<int>(std::max_element(pool.begin(), pool.end(),
                                          [](auto& a, auto& b) { return a.fitness < b.fitness; }) -
                         pool.begin());
    CHECK(survivors.front() == best);  // layer 0, highest fitness first
    // The only age-0 member cannot be dominated (nobody is younger): it is in layer 0.
    CHECK(pareto_ranks(pool, false)[100] == 0);
    // Every survivor outranks or ties every non-survivor's layer.
    const auto rank = pareto_ranks(pool, false);
    int worst_kept = 0, best_dropped = 1000;
    for (int i = 0; i < 101; ++i) {
        const bool kept = std::find(survivors.begin(), survivors.end(), i) != survivors.end();
        if (kept)
            worst_kept = std::max(worst_kept, rank[i]);
        else
            best_dropped = std::min(best_dropped, rank[i]);
    }
    CHECK(worst_kept <= best_dropped);
    // Deterministic: the same pool in another order selects the same ids.
    std::vector<AfpoObjectives> reversed(pool.rbegin(), pool.rend());
    const auto again = select_survivors(reversed, 50, false);
    for (std::size_t k = 0; k < 50; ++k)
        CHECK(reversed[again[k]].id == pool[survivors[k]].id);
}
