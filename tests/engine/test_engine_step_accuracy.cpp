// The accuracy gate of the time step on the paper's actuation scenes: at the default dt_fraction
// every voxel's trajectory stays within 1 % RMS of its swing of the converged reference, the same
// scene at dt_fraction 0.2 (tests/support/step_accuracy.hpp; one at a 2.2x longer step agrees
// with it within 0.006 %). A longer default step, or another time integration of the bond damping,
// has to keep this: the explicit bond damping left uncapped at twice the default step diverges and
// fails it. It compares the engine with itself, so it measures the error of the discretisation; a
// change of the damping law itself is measured against the old law (docs/physics.md, "Damping and
// the step").
#include <doctest/doctest.h>

#include "engine_test_bodies.hpp"
#include "support/step_accuracy.hpp"

using namespace bhm::engine;
using namespace bhm::engine::test;

namespace {

constexpr double kGate = 0.01;  // RMS error over swing
constexpr int kSamples = 60;

void check_scenes(double amplitude_c, double end_s, double dt_fraction = 0.9,
                  double rotary_inertia_scale = 1.0) {
    for (Scene scene : {Scene::AllActive, Scene::Banded, Scene::Framed}) {
        CAPTURE(static_cast<int>(scene));
        BodySpec spec = paper_scene(scene, amplitude_c);
        spec.dt_fraction = dt_fraction;
        spec.rotary_inertia_scale = rotary_inertia_scale;
        const bhm::test::TrajectoryError e = bhm::test::step_error(spec, end_s, kSamples);
        MESSAGE("scene " << static_cast<int>(scene) << " at " << amplitude_c << " degC: RMS error "
                         << e.rms_m << " m over a swing of " << e.swing_m << " m ("
                         << 100.0 * e.relative() << " %)");
        CHECK(e.swing_m > 1e-3);  // the scene moves: the gate compares motion, not rest
        CHECK(e.relative() < kGate);
    }
}

}  // namespace

TEST_CASE("step accuracy: the paper's scenes at 14.47 degC follow the converged reference") {
    // Through the expansion peak (0.175 s) and back.
    check_scenes(14.47, 0.3);
}

TEST_CASE("step accuracy: the paper's scenes at 39 degC follow the converged reference") {
    // Actuation strain 0.39: through the expansion peak and to the contraction peak (0.425 s).
    check_scenes(39.0, 0.45);
}

TEST_CASE("step accuracy: the paper's scenes at the presets' longer step follow the reference") {
    // The shipped experiments run dt_fraction 1.2 with rotary inertia scale 1.5 (1.59x the
    // default's step at 14.47 degC; issue 42, docs/benchmarks.md "a longer step"), against the
    // same unscaled reference: measured 0.05-0.16 % at 14.47 degC, 0.04-0.10 % at 39 degC.
    check_scenes(14.47, 0.3, 1.2, 1.5);
    check_scenes(39.0, 0.45, 1.2, 1.5);
}
