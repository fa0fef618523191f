// BodySpec::rotary_inertia_scale (issue 42): scaling the voxels' rotational inertia by s slows
// the links' rotational modes by 1 / sqrt(s), and the stable step follows them until the axial
// mode bounds it. The truth is the closed-form modes of a link between two paper voxels
// (E 5 MPa, rho 1000 kg/m^3, nu 0.35, L 1 cm, size scale 1 + 0.01 x 14.47 at the peak):
// axial scale M / (rho L^2), M = E (1 - nu) / ((1 + nu)(1 - 2 nu)) (P-wave modulus); bending
// scale^2 (4 E I / L) / (s m L^2 / 6) = scale^2 2 E / (s rho L^2) (I = L^4 / 12); the step
// 0.9 x 2.2 / (2 pi omega_max) (docs/physics.md, "Time step" and "Damping and the step").
#include <doctest/doctest.h>

#include <algorithm>
#include <cmath>
#include <numbers>

#include "engine_test_bodies.hpp"

using namespace bhm::engine;
using namespace bhm::engine::test;

namespace {

double expected_dt(double s) {
    const double E = 5e6, rho = 1000.0, nu = 0.35, L = 0.01, scale = 1.0 + 0.01 * 14.47;
    const double m_over_e = (1.0 - nu) / ((1.0 + nu) * (1.0 - 2.0 * nu));
    const double axial = scale * m_over_e * E / (rho * L * L);
    const double bending = scale * scale * 2.0 * E / (s * rho * L * L);
    return 0.9 * 2.2 / (2.0 * std::numbers::pi * std::sqrt(std::max(axial, bending)));
}

}  // namespace

TEST_CASE("rotary inertia scale: the step follows the rotational mode, then the axial one") {
    for (double s : {1.0, 1.2, 1.5, 4.0}) {
        CAPTURE(s);
        BodySpec spec = paper_scene(Scene::AllActive, 14.47);
        spec.rotary_inertia_scale = s;
        const double dt = Model::build(spec)->dt_s();
        CHECK(dt == doctest::Approx(expected_dt(s)).epsilon(1e-9));
    }
    // At the paper's nu 0.35 the bending mode bounds the step until s = 1.426: 1.19x longer then.
    CHECK(expected_dt(4.0) / expected_dt(1.0) == doctest::Approx(1.194).epsilon(1e-3));
}
