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
