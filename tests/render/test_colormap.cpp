// Colour maps: ends, monotone lightness where it matters, wrap-around where it must.
#include <doctest/doctest.h>

#include <cmath>
#include <limits>

#include <glm/glm.hpp>

#include "render/colormap.hpp"

using namespace bhm::render;

namespace {
float luma(glm::vec4 c) {
    return 0.2126f * c.r + 0.7152f * c.g + 0.0722f * c.b;
}
}  // namespace

TEST_CASE("the sequential map gets lighter monotonically from dark to light") {
    float previous = -1.0f;
    for (int i = 0; i <= 100; ++i) {
        const float l = luma(sample_color_map(ColorMapName::Sequential, i / 100.0f));
        CHECK(l > previous);
        previous = l;
    }
    CHECK(luma(sample_color_map(ColorMapName::Sequential, 0.0f)) < 0.15f);
    CHECK(luma(sample_color_map(ColorMapName::Sequential, 1.0f)) > 0.8f);
    CHECK(sample_color_map(ColorMapName::Sequential, -3.0f) ==
          sample_color_map(ColorMapName::Sequential, 0.0f));
    CHECK(sample_color_map(ColorMapName::Sequential, 7.0f) ==
          sample_color_map(ColorMapName::Sequential, 1.0f));
}

TEST_CASE("the diverging map is white-ish in the middle, blue below and red above") {
    const glm::vec4 mid = sample_color_map(ColorMapName::Diverging, 0.5f);
    CHECK(mid.r > 0.9f);
    CHECK(mid.g > 0.9f);
    CHECK(mid.b > 0.9f);
    const glm::vec4 low = sample_color_map(ColorMapName::Diverging, 0.0f);
    const glm::vec4 high = sample_color_map(ColorMapName::Diverging, 1.0f);
    CHECK(low.b > low.r);
    CHECK(high.r > high.b);
}

TEST_CASE("the cyclic map wraps: phase 0 and a full turn get the same colour") {
    const glm::vec4 a = sample_color_map(ColorMapName::Cyclic, 0.0f);
    const glm::vec4 b = sample_color_map(ColorMapName::Cyclic, 1.0f);
    const glm::vec4 half = sample_color_map(ColorMapName::Cyclic, 0.5f);
    CHECK(a.r == doctest::Approx(b.r));
    CHECK(a.g == doctest::Approx(b.g));
    CHECK(a.b == doctest::Approx(b.b));
    CHECK(glm::length(glm::vec3(a) - glm::vec3(half)) > 0.5f);
}

TEST_CASE("scalar ranges normalise and clamp, an empty range maps to the middle") {
    const ScalarRange range{2.0f, 6.0f};
    CHECK(range.normalize(2.0f) == 0.0f);
    CHECK(range.normalize(5.0f) == doctest::Approx(0.75f));
    CHECK(range.normalize(10.0f) == 1.0f);
    CHECK(range.normalize(-1.0f) == 0.0f);
    CHECK(ScalarRange{3.0f, 3.0f}.normalize(3.0f) == 0.5f);
    CHECK(parse_color_map("diverging") == ColorMapName::Diverging);
    CHECK_FALSE(parse_color_map("jet"));
}

TEST_CASE("colour maps and ranges take any float, finite or not, and give colours in [0, 1]") {
    const float inf = std::numeric_limits<float>::infinity();
    const float nan = std::numeric_limits<float>::quiet_NaN();
    const float big = std::numeric_limits<float>::max();
    const float inputs[] = {nan, inf, -inf, big, -big, 1e-45f, -0.0f, 0.5f, 1e30f, -1e30f};
    for (const ColorMapName map :
         {ColorMapName::Sequential, ColorMapName::Diverging, ColorMapName::Cyclic}) {
        for (const float t : inputs) {
            const glm::vec4 c = sample_color_map(map, t);
            for (int k = 0; k < 4; ++k) {
                CHECK(std::isfinite(c[k]));
                CHECK(c[k] >= 0.0f);
                CHECK(c[k] <= 1.0f);
            }
        }
        CHECK(sample_color_map(map, nan) == sample_color_map(map, 0.0f));
    }
    // Ranges from a replay with infinite or huge voxel sizes: the strain range was NaN.
    const ScalarRange ranges[] = {{-inf, inf},  {nan, nan},    {0.0f, nan},  {-big, big},
                                  {0.0f, 0.0f}, {1.0f, -1.0f}, {-1.0f, 1.0f}};
    for (const auto& range : ranges)
        for (const float v : inputs) {
            const float t = range.normalize(v);
            CHECK(t >= 0.0f);
            CHECK(t <= 1.0f);
        }
    CHECK(ScalarRange{-inf, inf}.normalize(3.0f) == 0.5f);
    CHECK(ScalarRange{-1.0f, 1.0f}.normalize(inf) == 1.0f);
    CHECK(ScalarRange{-1.0f, 1.0f}.normalize(-inf) == 0.0f);
    CHECK(ScalarRange{-1.0f, 1.0f}.normalize(nan) == 0.5f);
}

TEST_CASE("a field's colour scale is found in double over finite values and stays finite") {
    // Issue 41: a replay holding 3.4e38 (finite, a float's largest) gave a "-inf to inf" scale:
    // the largest magnitude, found in float, overflowed, and so did the span.
    const double inf = std::numeric_limits<double>::infinity();
    const double big = std::numeric_limits<float>::max();  // 3.4e38
    ScalarExtent extent;
    for (const double v : {0.5, -2.0, std::numeric_limits<double>::quiet_NaN(), inf, -inf})
        extent.add(v);
    CHECK(extent.largest() == 2.0);  // the non-finite values left out
    CHECK(extent.range(true, 0.1).min == -2.0f);
    CHECK(extent.range(true, 0.1).max == 2.0f);
    CHECK(extent.range(false, 1.0).min == 0.0f);
    extent.add(big);
    extent.add(big * 1e3);  // a displacement of 3.4e38 m in voxel lengths of 1 mm: finite in double
    for (const bool symmetric : {false, true}) {
        const ScalarRange range = extent.range(symmetric, 1.0);
        INFO("symmetric " << symmetric << ": " << range.min << " to " << range.max);
        CHECK(std::isfinite(range.min));
        CHECK(std::isfinite(range.max));
        CHECK(std::isfinite(range.max - range.min));           // the span, in float
        CHECK(std::isfinite(0.5f * (range.min + range.max)));  // the legend's middle
        CHECK(range.max == static_cast<float>(kMaxScaleMagnitude));
        CHECK(range.normalize(static_cast<float>(big)) == 1.0f);
        CHECK(range.normalize(range.max * 0.5f) ==
              doctest::Approx(symmetric ? 0.75 : 0.5).epsilon(1e-6));
    }
    // Nothing finite above zero: the fallback.
    ScalarExtent none;
    none.add(inf);
    none.add(0.0);
    CHECK(none.range(true, 0.1).max == 0.1f);
    CHECK(none.range(false, 1.0).max == 1.0f);
    // A range whose span overflows a float still normalises (in double), not 0.5 everywhere.
    const ScalarRange widest{-static_cast<float>(big), static_cast<float>(big)};
    CHECK(widest.normalize(0.0f) == 0.5f);
    CHECK(widest.normalize(static_cast<float>(big)) == 1.0f);
    CHECK(widest.normalize(-static_cast<float>(big) * 0.5f) == doctest::Approx(0.25));
}
