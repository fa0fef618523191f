// Floor contact and Coulomb friction.
#include <doctest/doctest.h>

#include <cmath>

#include "engine_test_bodies.hpp"
#include "support/relative_approx.hpp"

using namespace bhm::engine;
using namespace bhm::engine::test;

namespace {

// A 2x2x1 block resting on the floor (mu_s = 1, mu_k = 0.5); after settling, every voxel is pushed
// along +x with `ratio` times its weight. Returns the x travel (m) over the next `seconds`.
double travel_under_push(double ratio, double seconds) {
    BodySpec s = solid_box(2, 2, 1);
    s.environment.floor = true;
    s.environment.gravity_m_s2 = -9.81;
    s.damping.global_ratio = 0.0;  // no drag: friction alone resists the push
    auto model = Model::build(s);
    World w(model);
    REQUIRE(w.advance_to(0.2));
    const double mass = model->total_mass_kg() / model->voxel_count();
    for (int v = 0; v < model->voxel_count(); ++v)
        w.set_external_force(v, {ratio * mass * 9.81, 0, 0});
    const double x0 = w.centre_of_mass_m()[0];
    REQUIRE(w.advance_to(0.2 + seconds));
    return w.centre_of_mass_m()[0] - x0;
}

}  // namespace

TEST_CASE("a voxel on the floor rests at half its size above it") {
    BodySpec s = solid_box(1, 1, 1);
    s.environment.floor = true;
    s.environment.gravity_m_s2 = -9.81;
    World w(Model::build(s));
    REQUIRE(w.advance_to(0.3));
    const double L = s.voxel_size_m;
    // Penalty stiffness E L: it sinks m g / (E L) into the floor.
    const double sink = 1000.0 * L * L * L * 9.81 / (5e6 * L);
    CHECK(w.voxel_position_m(0)[2] == bhm::test::relative(0.5 * L - sink, 1e-4));
    CHECK(w.kinetic_energy_j() < 1e-12);
}

TEST_CASE("static friction holds a block pushed below mu_s m g") {
    const double travel = travel_under_push(0.9, 0.2);
    MESSAGE("travel at 0.9 m g: " << travel << " m");
    CHECK(std::fabs(travel) < 1e-7);
}

TEST_CASE("a block pushed above mu_s m g slides against kinetic friction mu_k m g") {
    const double seconds = 0.1;
    const double travel = travel_under_push(1.2, seconds);
    const double expected = 0.5 * (1.2 - 0.5) * 9.81 * seconds * seconds;  // a = (1.2 - mu_k) g
    MESSAGE("travel at 1.2 m g: " << travel << " m, expected " << expected << " m");
    CHECK(travel == bhm::test::relative(expected, 0.03));
}

TEST_CASE("without a floor the body falls freely") {
    BodySpec s = solid_box(2, 1, 1);
    s.environment.gravity_m_s2 = -9.81;
    s.damping.global_ratio = 0.0;
    World w(Model::build(s));
    const double z0 = w.centre_of_mass_m()[2];
    REQUIRE(w.advance_to(0.1));
    CHECK(z0 - w.centre_of_mass_m()[2] ==
          bhm::test::relative(0.5 * 9.81 * w.time_s() * w.time_s(), 1e-3));
}
