#pragma once
// Golden-image comparison: the rendered image against assets/golden/NAME.png with a small
// tolerance. BHM_UPDATE_GOLDEN=1 rewrites the golden instead. On a mismatch the actual image and
// an amplified difference go to <build>/golden-failures/ and the message says where.
#include <doctest/doctest.h>

#include <cstdlib>
#include <filesystem>
#include <string>

#include "render/image.hpp"

namespace bhm::render::testing {

inline constexpr double kMaxMeanDiff = 1.0 / 255.0;  // mean over all channels
inline constexpr double kMaxFractionOver = 0.005;    // pixels differing by more than 16

inline void check_golden(const std::string& name, const Image& actual) {
    const auto golden =
        std::filesystem::path(BHM_SOURCE_DIR) / "assets" / "golden" / (name + ".png");
    const char* update = std::getenv("BHM_UPDATE_GOLDEN");
    if (update && std::string(update) == "1") {
        std::filesystem::create_directories(golden.parent_path());
        write_png(golden.string(), actual);
        MESSAGE("updated golden " << golden.string());
        return;
    }
    REQUIRE_MESSAGE(std::filesystem::exists(golden),
                    golden.string() << " is missing: run with BHM_UPDATE_GOLDEN=1 to create it");
    const Image expected = read_png(golden.string());
    const ImageDifference d = compare_images(actual, expected, 16);
    const bool ok =
        d.same_size && d.mean_abs_diff < kMaxMeanDiff && d.fraction_over < kMaxFractionOver;
    if (!ok) {
        const auto dir = std::filesystem::path(BHM_BINARY_DIR) / "golden-failures";
        std::filesystem::create_directories(dir);
        write_png((dir / (name + "-actual.png")).string(), actual);
        if (d.same_size) write_png((dir / (name + "-diff.png")).string(), d.diff);
        FAIL_CHECK(name << " differs from " << golden.string() << ": mean diff "
                        << d.mean_abs_diff * 255.0 << "/255, " << d.fraction_over * 100.0
                        << " % of pixels off by > 16, max " << d.max_diff
                        << (d.same_size ? "" : ", sizes differ") << "; actual and diff in "
                        << dir.string());
    }
}

}  // namespace bhm::render::testing
