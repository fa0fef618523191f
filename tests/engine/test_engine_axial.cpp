// A bar pulled by a known end force stretches F l / (E A); links of two materials act in series.
#include <doctest/doctest.h>

#include <cmath>

#include "engine_test_bodies.hpp"
#include "support/relative_approx.hpp"

using namespace bhm::engine;
using namespace bhm::engine::test;

namespace {

// Pulls the x = nx - 1 layer of a fixed-at-x=0 bar with `force` (N, total) and returns the
// static stretch of that layer (m).
double stretch_under(BodySpec s, double force) {
    fix_x_min_layer(s);
    s.damping.bond_ratio = 1.0;
    s.damping.global_ratio = 0.05;
    auto model = Model::build(s);
    World w(model);
    int end_voxels = 0;
    for (int v = 0; v < model->voxel_count(); ++v)
        if (model->voxel_coords(v)[0] == s.nx - 1) ++end_voxels;
    for (int v = 0; v < model->voxel_count(); ++v)
        if (model->voxel_coords(v)[0] == s.nx - 1)
            w.set_external_force(v, {force / end_voxels, 0, 0});
    REQUIRE(w.advance_to(0.05));
    const double early = layer_displacement(w, s.nx - 1, 0);
    REQUIRE(w.advance_to(0.1));
    const double late = layer_displacement(w, s.nx - 1, 0);
    CHECK(late == bhm::test::relative(early, 1e-3));  // static
    return late;
}

}  // namespace

TEST_CASE("axial: a 10x1x1 bar stretches F l / (E A) within 2%") {
    const BodySpec s = solid_box(10, 1, 1);
    const double L = s.voxel_size_m, E = s.materials[0].youngs_modulus_pa;
    const double force = 5.0;  // ~1% strain
    const double l = 9.0 * L;  // from the fixed voxel's centre to the loaded voxel's centre
    const double expected = force * l / (E * L * L);
    const double stretch = stretch_under(s, force);
    MESSAGE("stretch " << stretch << " m, F l / (E A) = " << expected << " m");
    CHECK(stretch == bhm::test::relative(expected, 0.02));
}

TEST_CASE("axial: a 10x2x2 bar carries the force on four times the area") {
    const BodySpec s = solid_box(10, 2, 2);
    const double L = s.voxel_size_m, E = s.materials[0].youngs_modulus_pa;
    const double force = 20.0;
    const double expected = force * 9.0 * L / (E * 4.0 * L * L);
    CHECK(stretch_under(s, force) == bhm::test::relative(expected, 0.02));
}

TEST_CASE("axial: links between two materials are springs in series") {
    // Alternating E and 3E voxels: every link has E_link = 2 E 3E / (E + 3E) = 1.5 E.
    BodySpec s = solid_box(10, 1, 1);
    Material stiff = s.materials[0];
    stiff.youngs_modulus_pa *= 3.0;
    s.materials.push_back(stiff);
    for (int x = 1; x < 10; x += 2)
        s.material[s.cell_index(x, 0, 0)] = 2;
    const double L = s.voxel_size_m, E = s.materials[0].youngs_modulus_pa;
    const double force = 5.0;
    const double expected = force * 9.0 * L / (1.5 * E * L * L);
    CHECK(stretch_under(s, force) == bhm::test::relative(expected, 0.02));
}
