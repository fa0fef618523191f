#pragma once
// Shared by the studio tests: tiny experiments (a generation in about a second), fresh output
// folders, scripts whose waits allow for a loaded machine, and golden-image checks of studio
// screenshots.
#include <doctest/doctest.h>

#include <cstdint>
#include <cstdlib>
#include <filesystem>
#include <functional>
#include <memory>
#include <string>

#include <nlohmann/json.hpp>

#include "app/gui/shell/script.hpp"
#include "app/gui/studio.hpp"
#include "evo/experiment/experiment.hpp"
#include "render/image.hpp"
#include "support/scratch.hpp"
#include "support/wait_limit.hpp"

namespace bhm::app::gui::testing {

inline std::filesystem::path fresh_dir(const std::string& name) {
    return bhm::test::output_dir("studio", name);
}

//! Asks the studio's simulator for the 2x2x1 body {1, 2, 1, 2} (passive and active voxels side by
//! side) under `e`, as individual `id` named `label`; the caller's script waits for it
//! ({"wait_simulation": true}).
inline void request_tiny_body(Studio& studio, const evo::Experiment& e, std::int64_t id,
                              const std::string& label) {
    SimulationRequest request;
    request.id = id;
    request.label = label;
    request.experiment = e;
    auto body = std::make_shared<evo::Body>();
    body->size = {2, 2, 1};
    body->cells = {1, 2, 1, 2};
    request.framed_body = body;
    studio.bodies.simulator.request(request);
}

//! Paper Table 1 materials on a small workspace held at x-; short times so a generation of a
//! population of 4 takes about a second on one core.
inline evo::Experiment tiny_experiment(std::array<int, 3> size = {3, 2, 2}) {
    evo::Experiment e;
    e.name = "tiny";
    e.workspace_size = size;
    evo::MaterialEntry passive;
    passive.name = "passive tissue";
    passive.physics.cte_per_c = 0.0;
    evo::MaterialEntry active = passive;
    active.name = "muscle";
    active.physics.cte_per_c = 0.01;
    e.materials = {passive, active};
    e.boundary.faces[static_cast<int>(evo::Face::XMin)] = evo::BoundaryKind::Fixed;
    e.simulation.settle_s = 0.1;
    e.simulation.evaluate_s = 0.3;
    e.fitness.measure = evo::FitnessMeasure::BendAngleDeg;
    e.fitness.constraints.attached_to_fixed_face = true;
    e.evolution.population = 4;
    e.evolution.generations = 2;
    e.evolution.seed = 5;
    e.evolution.threads = 1;
    return e;
}

//! run_script with every step's timeout_s set to bhm::test::wait_limit_s() (the steps that wait
//! read it, the others ignore it): a test's script waits on its conditions however loaded the
//! machine, and a passing run is no slower (tests/support/wait_limit.hpp, issue 41).
inline void run_script_patiently(
    HeadlessStudio& session, nlohmann::json steps,
    const std::function<void(int, const nlohmann::json&)>& after_step = {}) {
    for (auto& step : steps)
        if (step.is_object() && !step.empty()) step["timeout_s"] = bhm::test::wait_limit_s();
    run_script(session, steps, after_step);
}

//! Draws frames until done() holds, for at most bhm::test::wait_limit_s(); whether it held
//! (REQUIRE it at the call, so a failure points there).
template <class Done>
bool frames_until(HeadlessStudio& session, Done done) {
    return bhm::test::wait_until(done, [&] { session.frame(); });
}

inline constexpr double kMaxMeanDiff = 1.5 / 255.0;
inline constexpr double kMaxFractionOver = 0.006;

//! Compares with assets/golden/studio-NAME.png (BHM_UPDATE_GOLDEN=1 rewrites it). The goldens
//! were drawn with DejaVu Sans; with another font only the size is compared.
inline void check_studio_golden(const std::string& name, const render::Image& actual,
                                const std::string& font) {
    const auto golden =
        std::filesystem::path(BHM_SOURCE_DIR) / "assets" / "golden" / ("studio-" + name + ".png");
    const char* update = std::getenv("BHM_UPDATE_GOLDEN");
    if (update && std::string(update) == "1") {
        render::write_png(golden.string(), actual);
        MESSAGE("updated golden " << golden.string());
        return;
    }
    REQUIRE_MESSAGE(std::filesystem::exists(golden),
                    golden.string() << " is missing: run with BHM_UPDATE_GOLDEN=1 to create it");
    const render::Image expected = render::read_png(golden.string());
    CHECK(expected.width == actual.width);
    CHECK(expected.height == actual.height);
    if (font != "DejaVu Sans") {
        MESSAGE("skipping the pixel comparison of " << name
                                                    << ": the goldens use DejaVu Sans, "
                                                       "this machine has "
                                                    << font);
        return;
    }
    const auto d = render::compare_images(actual, expected, 16);
    if (d.same_size && d.mean_abs_diff < kMaxMeanDiff && d.fraction_over < kMaxFractionOver) return;
    const auto dir = std::filesystem::path(BHM_BINARY_DIR) / "golden-failures";
    std::filesystem::create_directories(dir);
    render::write_png((dir / ("studio-" + name + "-actual.png")).string(), actual);
    if (d.same_size) render::write_png((dir / ("studio-" + name + "-diff.png")).string(), d.diff);
    FAIL_CHECK("studio-" << name << " differs from " << golden.string() << ": mean diff "
                         << d.mean_abs_diff * 255.0 << "/255, " << d.fraction_over * 100.0
                         << " % of pixels off by > 16; actual and diff in " << dir.string());
}

}  // namespace bhm::app::gui::testing
