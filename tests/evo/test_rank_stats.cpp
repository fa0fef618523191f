// bench_controllers' statistics (tests/bench/rank_stats.hpp) against values from tables and
// hand counts: the exact Mann-Whitney distribution, Kruskal-Wallis' H, the t interval.
#include <doctest/doctest.h>

#include <cmath>

#include "tests/bench/rank_stats.hpp"

using namespace bhm::bench;

TEST_CASE("bench statistics: Mann-Whitney exact p, Kruskal-Wallis H, the 95 % t interval") {
    // Complete separation of 5 and 5: U = 0, one arrangement of C(10, 5) = 252 per tail.
    const auto separated = mann_whitney({1, 2, 3, 4, 5}, {6, 7, 8, 9, 10});
    CHECK(separated.exact);
    CHECK(separated.statistic == 0.0);
    CHECK(separated.p == doctest::Approx(2.0 / 252.0).epsilon(1e-12));
    // 3 and 3: U counts 1, 1, 2, 3, 3, 3, 3, 2, 1, 1 over 20 arrangements; {1, 2, 4} against
    // {3, 5, 6} has one pair x > y, so p = 2 (1 + 1) / 20.
    const auto counts = u_counts(3, 3);
    const std::vector<double> expected = {1, 1, 2, 3, 3, 3, 3, 2, 1, 1};
    CHECK(counts == expected);
    const auto small = mann_whitney({1, 2, 4}, {3, 5, 6});
    CHECK(small.statistic == 1.0);
    CHECK(small.p == doctest::Approx(0.2).epsilon(1e-12));
    CHECK(mann_whitney({6, 5, 3}, {4, 2, 1}).p == doctest::Approx(0.2).epsilon(1e-12));
    // Ties: the normal approximation; identical samples give no evidence.
    const auto tied = mann_whitney({1, 1, 2}, {1, 1, 2});
    CHECK_FALSE(tied.exact);
    CHECK(tied.p == doctest::Approx(1.0));

    // {1,2,3}, {4,5,6}, {7,8,9}: rank sums 6, 15, 24; H = 12 / 90 x 279 - 30 = 7.2, p = e^-3.6.
    const auto kw = kruskal_wallis({{1, 2, 3}, {4, 5, 6}, {7, 8, 9}});
    CHECK(kw.statistic == doctest::Approx(7.2).epsilon(1e-12));
    CHECK(kw.p == doctest::Approx(std::exp(-3.6)).epsilon(1e-12));

    // {1..5}: mean 3, sd sqrt(2.5), t(0.975, 4) = 2.776.
    CHECK(ci95_half_width({1, 2, 3, 4, 5}) ==
          doctest::Approx(2.776 * std::sqrt(2.5) / std::sqrt(5.0)).epsilon(1e-12));
}
