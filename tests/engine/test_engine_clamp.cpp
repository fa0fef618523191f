// The clamp (docs/physics.md, "The clamp"; engine/model.cpp, "Held voxels' rotation"): held
// voxels keep their centres; those in a held face turn about the axes in the face, against a
// spring of their own material, never about its normal; a voxel held alone does not turn. How
// far the turning clamp moves the tip against CalculiX, and that a stiff layer held between soft
// ones does not hinge there: test_engine_calculix_mixed.cpp (the 100x layered cantilevers).
#include <doctest/doctest.h>

#include <cmath>

#include "engine_test_bodies.hpp"

using namespace bhm::engine;
using namespace bhm::engine::test;

namespace {

// The rotation vector (small turns: 2 q_vec) of voxel v.
std::array<double, 3> turn(const World& w, int v) {
    const auto q = w.voxel_orientation(v);
    const double s = q[0] < 0.0 ? -2.0 : 2.0;
    return {s * q[1], s * q[2], s * q[3]};
}

int voxel_at(const Model& m, const BodySpec& s, int x, int y, int z) {
    const int cell = s.cell_index(x, y, z);
    for (int v = 0; v < m.voxel_count(); ++v)
        if (m.voxel_cell(v) == cell) return v;
    FAIL("no voxel at (" << x << ", " << y << ", " << z << ")");
    return -1;
}

}  // namespace

TEST_CASE("clamp: a held face turns about the axes in it, never about its normal") {
    BodySpec s = solid_box(10, 2, 2);
    s.environment.gravity_m_s2 = -9.81;
    fix_x_min_layer(s);
    const auto model = Model::build(s);
    World w(model);
    REQUIRE(w.advance_to(0.3));
    for (int y = 0; y < 2; ++y)
        for (int z = 0; z < 2; ++z) {
            const auto held = turn(w, voxel_at(*model, s, 0, y, z));
            const auto next = turn(w, voxel_at(*model, s, 1, y, z));
            CAPTURE(y);
            CAPTURE(z);
            CHECK(w.voxel_position_m(voxel_at(*model, s, 0, y, z))[2] ==
                  doctest::Approx((z + 0.5) * s.voxel_size_m).epsilon(1e-12));
            // About the face's normal its spin is locked; what turn there is comes from composing
            // finite turns about y and z (second order).
            CHECK(std::fabs(held[0]) < 1e-3 * std::fabs(held[1]));
            // The beam sags (-z), so its sections turn about +y; the held end less than its
            // neighbour, held back by its spring.
            CHECK(next[1] > 1e-5);
            CHECK(held[1] > 0.0);
            CHECK(held[1] < 0.5 * next[1]);
        }
}

TEST_CASE("clamp: a voxel held alone does not turn") {
    BodySpec s = solid_box(12, 3, 3);
    s.environment.gravity_m_s2 = -9.81;
    s.fixed.assign(s.material.size(), 0);
    s.fixed[s.cell_index(1, 1, 1)] = 1;
    const auto model = Model::build(s);
    World w(model);
    REQUIRE(w.advance_to(0.2));
    const auto q = w.voxel_orientation(voxel_at(*model, s, 1, 1, 1));
    CHECK(q[0] == 1.0);
    CHECK(q[1] == 0.0);
    CHECK(q[2] == 0.0);
    CHECK(q[3] == 0.0);
    CHECK(std::fabs(turn(w, voxel_at(*model, s, 2, 1, 1))[1]) > 1e-6);  // its neighbours do
}
