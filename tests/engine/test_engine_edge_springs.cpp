// Springs across shared voxel edges (engine/internal/edge_springs.hpp): where they exist, that
// they conserve momentum, and that they follow actuation (a uniformly heated free body expands
// without stress). Their stiffness against CalculiX: test_engine_calculix_mixed.cpp.
#include <doctest/doctest.h>

#include <cmath>
#include <cstdint>
#include <numbers>

#include "engine_test_bodies.hpp"
#include "free_body_checks.hpp"

using namespace bhm::engine;
using namespace bhm::engine::test;

namespace {

// A free box whose voxel (x, y, z) is the stiffer material 2 (10x) when x + y + z is even.
BodySpec checkerboard(int nx, int ny, int nz, double cte_soft, double cte_stiff) {
    Material soft;
    soft.youngs_modulus_pa = 5e5;
    soft.poisson_ratio = 0.35;
    soft.cte_per_c = cte_soft;
    Material stiff = soft;
    stiff.youngs_modulus_pa = 5e6;
    stiff.cte_per_c = cte_stiff;
    BodySpec s = solid_box(nx, ny, nz, soft);
    s.materials.push_back(stiff);
    for (int z = 0; z < nz; ++z)
        for (int y = 0; y < ny; ++y)
            for (int x = 0; x < nx; ++x)
                s.material[s.cell_index(x, y, z)] = (x + y + z) % 2 == 0 ? 2 : 1;
    return s;
}

// Two by two in x, y: voxels (0, 0) and (1, 1) of material `ends`, (1, 0) and (0, 1) of
// `bridges` (0 = empty).
int springs_in_square(std::uint8_t ends, std::uint8_t bridge_a, std::uint8_t bridge_b) {
    Material soft;
    soft.youngs_modulus_pa = 5e5;
    Material stiff = soft;
    stiff.youngs_modulus_pa = 5e6;
    BodySpec s = solid_box(2, 2, 1, soft);
    s.materials.push_back(stiff);
    s.material[s.cell_index(0, 0, 0)] = ends;
    s.material[s.cell_index(1, 1, 0)] = ends;
    s.material[s.cell_index(1, 0, 0)] = bridge_a;
    s.material[s.cell_index(0, 1, 0)] = bridge_b;
    return Model::build(s)->edge_spring_count();
}

}  // namespace

TEST_CASE(
    "edge springs join stiff edge neighbours only where both voxels beside the edge are softer") {
    CHECK(springs_in_square(2, 1, 1) == 1);  // stiff diagonal, soft bridges
    CHECK(springs_in_square(1, 2, 2) == 1);  // the other diagonal is the stiff one
    CHECK(springs_in_square(2, 2, 1) == 0);  // a stiff bridge: the face lattice carries it
    CHECK(springs_in_square(2, 1, 0) == 0);  // a bridge missing
    CHECK(springs_in_square(1, 1, 1) == 0);  // one material
    CHECK(Model::build(solid_box(5, 4, 3))->edge_spring_count() == 0);
    // A 3x3x3 checkerboard: in each of its 9 3x3 squares (3 orientations, 3 layers) the stiff
    // voxels are either the centre and the 4 edge middles' neighbours or the corners and the
    // centre; either way 4 stiff diagonal pairs per square (stiff corners: each with the centre;
    // stiff edge middles: the 4 around the centre): 36.
    CHECK(Model::build(checkerboard(3, 3, 3, 0.0, 0.0))->edge_spring_count() == 36);
}

TEST_CASE(
    "edge springs: a free actuated checkerboard keeps its momentum, centre of mass and spin") {
    BodySpec s = checkerboard(4, 3, 3, 0.01, 0.0);
    s.phase_rad.assign(s.material.size(), 0.0f);
    for (int c = 0; c < s.cell_count(); ++c)
        s.phase_rad[c] = static_cast<float>(0.7 * c);
    s.actuation.start_s = 0.0;
    s.actuation.frequency_hz = 5.0;
    s.damping.global_ratio = 0.0;
    s.damping.bond_ratio = 0.5;
    auto model = Model::build(s);
    REQUIRE(model->edge_spring_count() > 0);
    World w(model);
    const double max_speed = check_free_body_keeps_momenta(w, 20, 0.01);
    CHECK(max_speed > 1e-3);  // the body really moved internally
}

TEST_CASE(
    "edge springs follow actuation: a uniformly heated free checkerboard expands without stress") {
    // Both materials expand by 1 % (a constant +1 degC): the free body's exact state is the rest
    // lattice scaled by 1.01, every voxel unturned. Springs that kept their rest length would pull
    // the stiff voxels' edges together and shear the body.
    BodySpec s = checkerboard(4, 4, 3, 0.01, 0.01);
    s.actuation.frequency_hz = 0.0;
    s.actuation.temperature_amplitude_c = 1.0;
    s.actuation.start_s = 0.0;
    s.phase_rad.assign(s.material.size(), static_cast<float>(std::numbers::pi / 2));
    s.damping.global_ratio = 0.2;
    auto model = Model::build(s);
    REQUIRE(model->edge_spring_count() > 0);
    World w(model);
    REQUIRE(w.advance_to(0.5));
    const double L = model->voxel_size_m();
    const auto com = w.centre_of_mass_m();
    double worst = 0.0;
    const auto rest_com = std::array<double, 3>{2.0 * L, 2.0 * L, 1.5 * L};
    for (int v = 0; v < model->voxel_count(); ++v) {
        const auto xyz = model->voxel_coords(v);
        const auto p = w.voxel_position_m(v);
        for (int i = 0; i < 3; ++i) {
            const double expected = com[i] + 1.01 * ((xyz[i] + 0.5) * L - rest_com[i]);
            worst = std::max(worst, std::fabs(p[i] - expected));
        }
    }
    MESSAGE("largest departure from the scaled lattice: " << worst / L << " L");
    CHECK(worst < 1e-5 * L);
}

namespace {

// A 2x2 square on the floor under gravity, x fastest: the anchor (0, 0), stiff (10x) and gripping
// the floor (mu_s 0.5), the bridges (1, 0) and (0, 1), its partner (1, 1), the last three
// frictionless. A force on the partner pulls away from the anchor along the diagonal, growing
// slowly to 3 mu_s times the anchor's weight over 3 s; the anchor counts as let go once it has
// slid 1e-3 L. Returns the pull then over mu_s N, N the anchor's floor force (its penalty spring
// E L times its depth).
double release_over_grip(int bridge_material, int* springs) {
    Material stiff_anchor;
    stiff_anchor.youngs_modulus_pa *= 10.0;
    stiff_anchor.static_friction = 0.5;
    stiff_anchor.dynamic_friction = 0.4;
    Material stiff_free = stiff_anchor;
    stiff_free.static_friction = stiff_free.dynamic_friction = 0.0;
    Material soft;
    soft.static_friction = soft.dynamic_friction = 0.0;
    BodySpec s = solid_box(2, 2, 1);
    s.materials = {stiff_anchor, stiff_free, soft};
    const auto bridge = static_cast<std::uint8_t>(bridge_material);
    s.material = {1, bridge, bridge, 2};
    s.environment.floor = true;
    s.environment.gravity_m_s2 = -9.81;
    auto model = Model::build(s);
    *springs = model->edge_spring_count();
    World w(model);
    REQUIRE(w.advance_to(0.3));  // settled on the floor
    const double L = model->voxel_size_m();
    const double weight = model->total_mass_kg() / 4.0 * 9.81;
    const auto start = w.voxel_position_m(0);
    const double normal = stiff_anchor.youngs_modulus_pa * L * (0.5 * L - start[2]);
    const double t0 = w.time_s(), ramp_s = 3.0, most = 3.0 * stiff_anchor.static_friction * weight;
    while (w.time_s() < t0 + ramp_s) {
        const double pull = most * (w.time_s() - t0) / ramp_s;
        w.set_external_force(3, {pull / std::sqrt(2.0), pull / std::sqrt(2.0), 0.0});
        w.step();
        if (w.diverged()) break;
        const auto p = w.voxel_position_m(0);
        if (std::hypot(p[0] - start[0], p[1] - start[1]) > 1e-3 * L)
            return pull / (stiff_anchor.static_friction * normal);
    }
    REQUIRE(!w.diverged());
    return 0.0;  // never let go
}

}  // namespace

TEST_CASE("edge springs: static friction weighs the springs' forces with the links'") {
    // With stiff bridges the pull reaches the anchor through links alone; with 10x softer ones
    // through the links and the spring across the stiff pair's shared edge. Coulomb's law lets
    // the anchor go at the same share of mu_s N either way (the anchor's N is larger on soft
    // bridges: the stiff contact carries more of the weight). Static friction that weighed the
    // links' share alone held it until 1.41 mu_s N instead of 0.86 (links alone: 0.90).
    int springs = -1;
    const double links_only = release_over_grip(2, &springs);
    CHECK(springs == 0);
    const double with_spring = release_over_grip(3, &springs);
    CHECK(springs == 1);
    MESSAGE("let go at " << links_only << " mu_s N on links alone, " << with_spring
                         << " mu_s N with the spring");
    CHECK(links_only > 0.5);
    CHECK(std::fabs(with_spring / links_only - 1.0) < 0.08);
}
