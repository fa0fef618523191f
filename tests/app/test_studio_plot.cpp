// Plot axes: auto-fitted ranges, round ticks, labels, medians and the hovered generation.
#include <doctest/doctest.h>

#include <cmath>
#include <limits>

#include "app/gui/widgets/fitness_plot.hpp"
#include "app/gui/widgets/plot_axes.hpp"

using namespace bhm::app::gui;

TEST_CASE("studio plot axes: ranges fit the finite data with padding") {
    const auto r = fit_range({2.0, 7.0, std::numeric_limits<double>::quiet_NaN(), 4.0}, 0.1);
    CHECK(r.min == doctest::Approx(1.5));
    CHECK(r.max == doctest::Approx(7.5));
    const auto flat = fit_range({3.0, 3.0});
    CHECK(flat.min == doctest::Approx(2.5));
    CHECK(flat.max == doctest::Approx(3.5));
    const auto none = fit_range({});
    CHECK(none.min == 0.0);
    CHECK(none.max == 1.0);
}

TEST_CASE("studio plot axes: ticks are round multiples of 1, 2 or 5 x 10^k inside the range") {
    auto ticks = nice_ticks({0.0, 1.0}, 5);
    REQUIRE(ticks.size() == 6);
    CHECK(ticks[1] == doctest::Approx(0.2));
    CHECK(ticks[5] == doctest::Approx(1.0));
    ticks = nice_ticks({-3.7, 41.2}, 5);
    REQUIRE(ticks.size() == 5);
    CHECK(ticks.front() == 0.0);
    CHECK(ticks.back() == 40.0);
    ticks = nice_ticks({1995.0, 2003.0}, 4);
    CHECK(ticks.front() == 1996.0);
    CHECK(ticks[1] - ticks[0] == 2.0);
    CHECK(nice_ticks({5.0, 5.0}).empty());
    CHECK(format_tick(0.25, 0.05) == "0.25");
    CHECK(format_tick(1200.0, 200.0) == "1200");
    CHECK(format_tick(3e6, 1e6) == "3e+06");
}

TEST_CASE("studio plot: median and the generation nearest to the mouse") {
    CHECK(median_of({5.0, 1.0, 3.0}) == 3.0);
    CHECK(median_of({4.0, 1.0, 3.0, 2.0}) == 2.5);
    CHECK(median_of({}) == 0.0);
    std::vector<GenerationRecord> history;
    for (int g : {0, 1, 2, 5, 9})
        history.push_back({g, 1.0 * g, 0.5 * g, 0.0, 0});
    CHECK(nearest_record(history, -4.0) == 0);
    CHECK(nearest_record(history, 1.4) == 1);
    CHECK(nearest_record(history, 3.6) == 3);  // generation 5
    CHECK(nearest_record(history, 7.1) == 4);
    CHECK(nearest_record(history, 99.0) == 4);
    CHECK(nearest_record({}, 1.0) == -1);
}
