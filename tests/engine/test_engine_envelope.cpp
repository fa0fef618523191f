// The actuation envelope: the paper's scenes (all-active 8x8x7 block, 4-voxel active/passive
// bands on 20x8x7, the framed paper-exp3 body) fixed at x-, on the floor under gravity, with the
// default damping and dt_fraction, run through a whole actuation period (the contraction peak
// included) at the largest strain the engine admits (limits::kMaxActuationStrain).
#include <doctest/doctest.h>

#include <algorithm>
#include <cmath>
#include <cstdint>

#include "engine/limits.hpp"
#include "engine/poses.hpp"
#include "engine_test_bodies.hpp"
#include "fuzz_random.hpp"

using namespace bhm::engine;
using namespace bhm::engine::test;

TEST_CASE("envelope: the paper's scenes survive the largest admitted actuation strain") {
    const double amplitude = limits::kMaxActuationStrain / 0.01;  // degC at cte 0.01
    for (Scene scene : {Scene::AllActive, Scene::Banded, Scene::Framed}) {
        CAPTURE(static_cast<int>(scene));
        auto model = Model::build(paper_scene(scene, amplitude));
        World w(model);
        // One whole 2 Hz period after the start: the expansion peak at 0.125 s, the contraction
        // peak (voxels at 1 - 0.6 of their size) at 0.375 s.
        const bool ok = w.advance_to(0.05 + 0.5);
        if (!ok) MESSAGE(w.divergence_reason());
        REQUIRE(ok);
        VoxelPoses poses;
        w.read_poses(poses);
        float lo = 1e9f, hi = -1e9f;
        for (float x : poses.position_m) {
            REQUIRE(std::isfinite(x));
            lo = std::min(lo, x);
            hi = std::max(hi, x);
        }
        // Bounded: nothing left the scene's box (the floor and the fixed face hold it).
        CHECK(lo > -0.01f);
        CHECK(hi < 0.3f);
    }
}

TEST_CASE("envelope: past the admitted strain, the engine refuses the spec") {
    BodySpec s = paper_scene(Scene::AllActive, 100.0 * limits::kMaxActuationStrain + 1.0);
    CHECK_THROWS_AS(Model::build(s), std::invalid_argument);
}

TEST_CASE("envelope: the stable step is computed at the largest actuated size") {
    // With the size s = 1 + cte A, axial stiffness grows as s and bending as s^2. At nu = 0.35
    // the axial mode (P-wave factor (1 - nu) / ((1 + nu) (1 - 2 nu)) = 1.605 x E L / m) is below
    // bending's 2 s^2 x E L / m both at rest and at s = 1.4 (2.25 against 3.92), so the step
    // shrinks as 1 / s; sized at rest it would be 1.4x too long for the actuated bending.
    const BodySpec still = paper_scene(Scene::AllActive, 0.0);
    const BodySpec moving = paper_scene(Scene::AllActive, 40.0);
    const double ratio = Model::build(moving)->dt_s() / Model::build(still)->dt_s();
    CHECK(std::fabs(ratio - 1.0 / 1.4) < 1e-9);
}

TEST_CASE("envelope: at the largest admitted dt_fraction the paper's block stays stable") {
    // The stable step follows the stiffest mode (with Poisson coupling the P-wave modulus M when
    // it is stiffer than bending): a step sized from bending alone diverges here at nu = 0.49
    // within 21 steps.
    for (double nu : {0.0, 0.35, 0.49}) {
        CAPTURE(nu);
        BodySpec s = paper_scene(Scene::AllActive, 14.47);
        for (Material& m : s.materials)
            m.poisson_ratio = nu;
        s.dt_fraction = limits::kMaxDtFraction;
        World w(Model::build(s));
        const bool ok = w.advance_to(0.05 + 0.5);
        if (!ok) MESSAGE(w.divergence_reason());
        CHECK(ok);
    }
}

TEST_CASE("envelope: random mixtures of a soft and a 100x stiffer material stay stable") {
    // A column's end estimate of the Poisson pass used to extrapolate through a stiffer partner
    // (poisson.cpp): the stress of a stiff far link over the soft end voxel's modulus weighted that
    // link's strain by up to E_far / E_v, a stiffness the step and the damping cap did not know.
    // Each of these bodies diverges on the engine before that rule; they must survive 0.02 s (tens
    // of thousands of steps) of actuation from t = 0, softer (k = 0.01) or stiffer (k = 100) second
    // material alike.
    for (int n : {4, 6})
        for (double nu : {0.2, 0.35})
            for (double k : {0.01, 100.0}) {
                CAPTURE(n);
                CAPTURE(nu);
                CAPTURE(k);
                Material soft;
                soft.poisson_ratio = nu;
                soft.cte_per_c = 0.01;
                Material other = soft;
                other.youngs_modulus_pa *= k;
                other.cte_per_c = 0.0;
                BodySpec s = solid_box(n, n, n, soft);
                s.materials.push_back(other);
                Random r{12345};
                for (std::uint8_t& m : s.material)
                    m = static_cast<std::uint8_t>(1 + r.below(2));
                s.actuation.start_s = 0.0;
                World w(Model::build(s));
                const bool ok = w.advance_to(0.02);
                if (!ok) MESSAGE(w.divergence_reason());
                CHECK(ok);
            }
}

namespace {

// A random body inside the admitted envelope: 3-6 voxels a side, holes, 2-3 materials whose E
// spans 10^4 and density 10^3, any admitted nu, moderate actuation, random damping ratios and
// dt_fraction, half of them held at x-, under 1 g on the floor.
BodySpec random_admitted_body(Random& r, int steps) {
    BodySpec s;
    s.nx = 3 + r.below(4);
    s.ny = 3 + r.below(4);
    s.nz = 3 + r.below(4);
    const double amplitude = 20.0;
    const double ratios[] = {-0.9, -0.5, 0.0, 0.2, 0.35, 0.45, 0.49};
    const int materials = 2 + r.below(2);
    for (int i = 0; i < materials; ++i) {
        Material m;
        m.youngs_modulus_pa = 5e6 * std::pow(10.0, -2.0 + 4.0 * r.uniform());
        m.density_kg_m3 = 1000.0 * std::pow(10.0, -1.5 + 3.0 * r.uniform());
        m.poisson_ratio = ratios[r.below(7)];
        m.cte_per_c = r.below(2) ? (r.below(4) ? 1.0 : -1.0) * r.uniform() * 0.15 / amplitude : 0.0;
        m.static_friction = 2.0 * r.uniform();
        m.dynamic_friction = m.static_friction * r.uniform();
        s.materials.push_back(m);
    }
    draw_cells_damping_and_step(r, s, materials);
    s.actuation.temperature_amplitude_c = amplitude;
    // A quarter period in `steps`: the actuation moves through its peak within the run.
    const double dt = Model::build(s)->dt_s();
    s.actuation.frequency_hz = std::min(1000.0, 0.25 / (steps * dt));
    return s;
}

}  // namespace

TEST_CASE("envelope: random bodies of several materials inside the envelope stay stable") {
    // Before the column-end rule (poisson.cpp) 117 of 600 such bodies (this generator, seeded 1)
    // diverged within 40,000 steps, and 15 of these 60 within 5,000; after it none did.
    const int steps = 5000;
    Random r{2026};
    int diverged = 0;
    for (int body = 0; body < 60; ++body) {
        const BodySpec s = random_admitted_body(r, steps);
        World w(Model::build(s));
        for (int i = 0; i < steps && !w.diverged(); ++i)
            w.step();
        if (w.diverged()) {
            ++diverged;
            MESSAGE("body " << body << ": " << w.divergence_reason());
        }
    }
    CHECK(diverged == 0);
}

namespace {
// 600 random admitted bodies (seeded 1), 40,000 steps each, their voxels' rotational inertia
// scaled by rotary_scale (BodySpec::rotary_inertia_scale, which lengthens the step with it).
void envelope_fuzz(double rotary_scale) {
    const int steps = 40000;
    Random r{1};
    int diverged = 0;
    for (int body = 0; body < 600; ++body) {
        BodySpec s = random_admitted_body(r, steps);
        s.rotary_inertia_scale = rotary_scale;
        World w(Model::build(s));
        for (int i = 0; i < steps && !w.diverged(); ++i)
            w.step();
        if (w.diverged()) {
            ++diverged;
            MESSAGE("body " << body << ": " << w.divergence_reason());
        }
    }
    MESSAGE(diverged << " of 600 diverged");
    CHECK(diverged == 0);
}
}  // namespace

// The long form of the case above, as docs/physics.md quotes it (600 bodies, 40,000 steps each,
// seeded 1; a few minutes): build/bin/test_engine -tc="envelope fuzz*" --no-skip
TEST_CASE("envelope fuzz: 600 random bodies of several materials, 40,000 steps" * doctest::skip()) {
    envelope_fuzz(1.0);
}

// The same with the rotary inertia scale that lets the axial mode bound the step (issue 42,
// docs/benchmarks.md "the step size itself"): the rotational modes slow, the step grows.
// BHM_FUZZ_ROT_SCALE sets another scale, BHM_FUZZ_DT_STRETCH stretches the drawn dt_fractions
// (tests/engine/fuzz_random.hpp; issue 42 "a longer step" runs 1.6, up to kMaxDtFraction).
TEST_CASE("rotary inertia envelope fuzz: 600 random bodies at scale 1.5, 40,000 steps" *
          doctest::skip()) {
    envelope_fuzz(fuzz_rotary_scale());
}
