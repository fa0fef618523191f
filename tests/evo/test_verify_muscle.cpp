// bhm verify on muscle bodies (issue 43): CalculiX's orthotropic expansion (the fibre's free
// strain per unit activation) against our engine held at full activation, on a muscle-on-passive
// strip whose fibres run along it, across it, or whose muscle lies beside the passive half. The
// loads are rest and peak activation only (a muscle only contracts). Each case solves a 40-voxel
// strip, C3D8I 2 per voxel edge, in a few seconds; they skip (loudly) only where ccx is missing.
#include <doctest/doctest.h>

#include "support/ccx_skip.hpp"

#include <cmath>
#include <cstdio>
#include <stdexcept>
#include <string>

#include "evo/verify/ccx_deck.hpp"
#include "evo/verify/fem_model.hpp"
#include "evo/verify/quasi_static.hpp"
#include "evo/verify/verify_body.hpp"

using namespace bhm;

namespace {

constexpr double kL = 0.01;
constexpr double kStrain = 0.02;  // free shortening along the fibre at full activation

using bhm::test::skip_without_ccx;

// A 10 x 2 x 2 strip of 5 MPa, held at its x = 0 layer, without gravity: its half on the minus
// side of `split_axis` (z: the bottom layer, y: the side at y = 0) is muscle whose fibres run
// along `fibre_axis`, the other half passive.
engine::BodySpec muscle_strip(int fibre_axis, double nu, int split_axis = 2) {
    engine::BodySpec s;
    s.nx = 10;
    s.ny = 2;
    s.nz = 2;
    s.voxel_size_m = kL;
    engine::Material passive;
    passive.youngs_modulus_pa = 5e6;
    passive.poisson_ratio = nu;
    engine::Material muscle = passive;
    muscle.actuation_model = engine::ActuationModel::Muscle;
    muscle.muscle.fibre_axis = fibre_axis;
    muscle.muscle.contraction_strain = kStrain;
    // A burst schedule the static answer must not depend on (it holds a = 1).
    muscle.muscle.frequency_hz = 20.0;
    muscle.muscle.train_on_s = 0.3;
    muscle.muscle.train_off_s = 0.2;
    s.materials = {passive, muscle};
    s.material.assign(static_cast<std::size_t>(s.cell_count()), 1);
    s.fixed.assign(static_cast<std::size_t>(s.cell_count()), 0);
    for (int z = 0; z < s.nz; ++z)
        for (int y = 0; y < s.ny; ++y)
            for (int x = 0; x < s.nx; ++x) {
                const auto c = static_cast<std::size_t>(s.cell_index(x, y, z));
                if ((split_axis == 2 ? z : y) == 0) s.material[c] = 2;
                if (x == 0) s.fixed[c] = 1;
            }
    s.environment.gravity_m_s2 = 0.0;
    s.damping.global_ratio = 0.01;
    return s;
}

// C3D8I 2 per voxel edge, steps nonlinear: linear ones miss the tip's foreshortening as the strip
// bends (measured at 4 deg: the tip differed by 4.6 %, nearly all along x, and by 0.5 % nonlinear).
evo::VerifyOptions strip_options() {
    evo::VerifyOptions o;
    o.mesh = evo::FemMeshOptions{evo::FemElement::C3D8I, 2};
    o.tolerance = 0.05;
    o.geometry = evo::FemGeometry::Nonlinear;
    return o;
}

const evo::LoadComparison& peak_of(const evo::BodyVerification& v) {
    REQUIRE(v.loads.size() == 2);  // rest and peak: no -A
    CHECK(v.loads[0].load == "rest");
    CHECK(v.loads[1].load == "peak");
    CHECK(v.loads[1].temperature_c == 1.0);  // the activation
    return v.loads[1];
}

std::string describe(const evo::LoadComparison& c) {
    char text[384];
    std::snprintf(text, sizeof text,
                  "tip FEM (%.3g, %.3g, %.3g) mm, engine (%.3g, %.3g, %.3g) mm; bend FEM %.3g deg, "
                  "engine %.3g deg; CoM y, z FEM %.3g, %.3g mm, engine %.3g, %.3g mm",
                  1e3 * c.fem.tip_m[0], 1e3 * c.fem.tip_m[1], 1e3 * c.fem.tip_m[2],
                  1e3 * c.engine.tip_m[0], 1e3 * c.engine.tip_m[1], 1e3 * c.engine.tip_m[2],
                  c.fem.bend_deg, c.engine.bend_deg, 1e3 * c.fem.com_m[1], 1e3 * c.fem.com_m[2],
                  1e3 * c.engine.com_m[1], 1e3 * c.engine.com_m[2]);
    return text;
}

}  // namespace

TEST_CASE("verify muscle: the deck's orthotropic expansion is the engine's free strain") {
    const auto s = muscle_strip(1, 0.35);
    const std::string deck = evo::ccx_deck(evo::build_fem_model(s, {evo::FemElement::C3D8I, 1}), s,
                                           {{"rest", 0.0}, {"peak", 1.0}}, false);
    // Fibres along y: -0.02 along them, +0.35 x 0.02 across (x and z), per unit activation.
    CHECK(deck.find("*EXPANSION, TYPE=ORTHO, ZERO=0.\n0.007, -0.02, 0.007\n") != std::string::npos);
    CHECK(evo::muscle_driven(s));
    auto passive = s;
    passive.materials[1].muscle.contraction_strain = 0.0;  // a muscle material that never acts
    CHECK_FALSE(evo::muscle_driven(passive));
    CHECK_THROWS_AS(evo::engine_quasi_static(s, 0.5), std::invalid_argument);  // only 0 or 1
}

TEST_CASE("verify muscle: fibres along a bilayer strip bend it down, engine within 5 % of ccx") {
    if (skip_without_ccx()) return;
    for (const double nu : {0.35, 0.0}) {
        CAPTURE(nu);
        const auto v = evo::verify_body(muscle_strip(0, nu), evo::FitnessMeasure::BendAngleDeg,
                                        strip_options());
        const auto& peak = peak_of(v);
        MESSAGE("nu " << nu << ": " << describe(peak) << "; " << v.verdict());
        CHECK(v.muscle);
        CHECK(v.verdict().find("peak activation (a muscle only contracts: no -A)") !=
              std::string::npos);
        // The bottom layer shortens: the tip goes down, the strip bends in the x-z plane.
        CHECK(peak.fem.tip_m[2] < -1e-3);
        CHECK(peak.engine.tip_m[2] < -1e-3);
        CHECK(std::fabs(peak.fem.com_m[1]) < 0.02 * std::fabs(peak.fem.com_m[2]));
        CHECK(std::fabs(peak.engine.com_m[1]) < 0.02 * std::fabs(peak.engine.com_m[2]));
        REQUIRE(peak.differences.tip);
        REQUIRE(peak.differences.bend);
        CHECK(*peak.differences.tip < 0.05);
        CHECK(*peak.differences.bend < 0.05);
        CHECK(v.agrees);
        if (nu == 0.0) {
            // The deck itself against Timoshenko's bilayer (equal layers: curvature 3 e / (2 h),
            // w = -kappa x^2 / 2 from the clamp plane through the held voxels' centres); measured
            // -6.01 mm against -6.08 mm.
            const double kappa = 1.5 * kStrain / (2 * kL), x = 9.0 * kL;
            CHECK(peak.fem.tip_m[2] == doctest::Approx(-kappa * x * x / 2).epsilon(0.03));
        }
    }
}

TEST_CASE("verify muscle: fibres across the strip bend it the other way or in the other plane") {
    if (skip_without_ccx()) return;
    // Fibres along y: the bottom layer lengthens along the strip by nu x strain, so the tip goes
    // up (the same x-z plane, the other way), about nu times as far as with fibres along x.
    {
        const auto v = evo::verify_body(muscle_strip(1, 0.35), evo::FitnessMeasure::BendAngleDeg,
                                        strip_options());
        const auto& peak = peak_of(v);
        MESSAGE("fibres along y: " << describe(peak) << "; " << v.verdict());
        CHECK(peak.fem.tip_m[2] > 3e-4);
        CHECK(peak.engine.tip_m[2] > 3e-4);
        CHECK(peak.fem.com_m[2] > 0.0);
        CHECK(peak.engine.com_m[2] > 0.0);
        CHECK(std::fabs(peak.fem.com_m[1]) < 0.02 * peak.fem.com_m[2]);
        CHECK(std::fabs(peak.engine.com_m[1]) < 0.02 * peak.engine.com_m[2]);
        REQUIRE(peak.differences.tip);
        CHECK(*peak.differences.tip < 0.05);
    }
    // The muscle beside the passive half (y = 0), fibres along x: the tip goes to -y, in the
    // x-y plane, and not up or down.
    {
        const auto v = evo::verify_body(muscle_strip(0, 0.35, 1), evo::FitnessMeasure::BendAngleDeg,
                                        strip_options());
        const auto& peak = peak_of(v);
        MESSAGE("muscle beside, fibres along x: " << describe(peak) << "; " << v.verdict());
        CHECK(peak.fem.tip_m[1] < -1e-3);
        CHECK(peak.engine.tip_m[1] < -1e-3);
        CHECK(std::fabs(peak.fem.com_m[2]) < 0.02 * std::fabs(peak.fem.com_m[1]));
        CHECK(std::fabs(peak.engine.com_m[2]) < 0.02 * std::fabs(peak.engine.com_m[1]));
        REQUIRE(peak.differences.tip);
        REQUIRE(peak.differences.bend);
        CHECK(*peak.differences.tip < 0.05);
        CHECK(*peak.differences.bend < 0.05);
    }
}
