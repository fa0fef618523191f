// The engine's cost and results follow the body, not its workspace: a sparse body gives the same
// trajectory bit for bit when it is embedded in a larger workspace, shifted by whole voxels, and
// the voxel and link counts are the body's own.
#include <doctest/doctest.h>

#include <cmath>
#include <cstdint>
#include <vector>

#include "engine/poses.hpp"
#include "engine_test_bodies.hpp"
#include "support/relative_approx.hpp"

using namespace bhm::engine;
using namespace bhm::engine::test;

namespace {

// A sparse, irregular body filling a 6 x 5 x 4 box from its corner: holes, isolated voxels, two
// materials, random-looking phases, and a few held voxels. Cell values come from a fixed hash.
BodySpec sparse_body(bool floor) {
    BodySpec s = solid_box(6, 5, 4);
    Material active = s.materials[0];
    active.cte_per_c = 0.01;
    s.materials.push_back(active);
    s.fixed.assign(s.material.size(), 0);
    s.phase_rad.assign(s.material.size(), 0.0f);
    std::uint32_t r = 12345u;
    for (int c = 0; c < s.cell_count(); ++c) {
        r = r * 1103515245u + 12345u;
        const int k = static_cast<int>((r >> 16) % 7);
        s.material[c] = static_cast<std::uint8_t>(k < 3 ? 0 : 1 + k % 2);
        s.phase_rad[c] = static_cast<float>(std::fmod(0.7 * c, 6.28));
    }
    s.material[s.cell_index(0, 0, 0)] = 1;  // the body touches every low face of its box
    s.material[s.cell_index(5, 4, 3)] = 2;  // ... and every high face
    s.fixed[s.cell_index(0, 0, 0)] = 1;
    s.environment.floor = floor;
    s.environment.gravity_m_s2 = -9.81;
    s.actuation.start_s = 0.005;
    s.actuation.frequency_hz = 20.0;
    return s;
}

// The same body inside a workspace `grow` cells larger on each axis, shifted by `shift` cells.
BodySpec embedded(const BodySpec& s, std::array<int, 3> grow, std::array<int, 3> shift) {
    BodySpec e = s;
    e.nx = s.nx + grow[0];
    e.ny = s.ny + grow[1];
    e.nz = s.nz + grow[2];
    const auto cells = static_cast<std::size_t>(e.cell_count());
    e.material.assign(cells, 0);
    e.fixed.assign(cells, 0);
    e.phase_rad.assign(cells, 2.5f);  // empty cells' phases must not matter
    for (int z = 0; z < s.nz; ++z)
        for (int y = 0; y < s.ny; ++y)
            for (int x = 0; x < s.nx; ++x) {
                const int from = s.cell_index(x, y, z);
                const int to = e.cell_index(x + shift[0], y + shift[1], z + shift[2]);
                e.material[to] = s.material[from];
                e.fixed[to] = s.fixed[from];
                e.phase_rad[to] = s.phase_rad[from];
            }
    return e;
}

void check_same_trajectory(const BodySpec& small, const BodySpec& big, std::array<int, 3> shift) {
    const auto a = Model::build(small), b = Model::build(big);
    REQUIRE(a->voxel_count() == b->voxel_count());
    REQUIRE(a->link_count() == b->link_count());
    CHECK(a->dt_s() == b->dt_s());
    const double L = small.voxel_size_m;
    World wa(a), wb(b);
    VoxelPoses pa, pb;
    for (int block = 0; block < 8; ++block) {
        for (int i = 0; i < 500; ++i) {
            wa.step();
            wb.step();
        }
        REQUIRE_FALSE(wa.diverged());
        REQUIRE_FALSE(wb.diverged());
        // The small body's origin is the world origin, so its reported positions are the
        // engine's own numbers; the embedded body's are the same numbers plus its offset.
        int mismatches = 0;
        for (int v = 0; v < a->voxel_count(); ++v) {
            const auto p = wa.voxel_position_m(v), q = wb.voxel_position_m(v);
            for (int k = 0; k < 3; ++k)
                mismatches += q[k] != p[k] + shift[k] * L;
            mismatches += wa.voxel_orientation(v) != wb.voxel_orientation(v);
        }
        CHECK(mismatches == 0);
        CHECK(wa.kinetic_energy_j() == wb.kinetic_energy_j());
        wa.read_poses(pa);
        wb.read_poses(pb);
        CHECK(pa.orientation == pb.orientation);
        CHECK(pa.size_m == pb.size_m);
    }
    // The comparison is between moving bodies, not two rest states.
    CHECK(wa.kinetic_energy_j() > 0.0);
    const auto com = wa.centre_of_mass_m(), com_b = wb.centre_of_mass_m();
    for (int k = 0; k < 3; ++k)
        CHECK(com_b[k] == bhm::test::relative(com[k] + shift[k] * L, 1e-12));
}

}  // namespace

TEST_CASE("a sparse body embedded in a larger workspace moves bit for bit the same") {
    SUBCASE("on the floor, shifted along x and y") {
        const BodySpec s = sparse_body(true);
        check_same_trajectory(s, embedded(s, {7, 4, 3}, {5, 2, 0}), {5, 2, 0});
    }
    SUBCASE("in free fall, shifted along every axis") {
        const BodySpec s = sparse_body(false);
        check_same_trajectory(s, embedded(s, {3, 9, 6}, {1, 8, 5}), {1, 8, 5});
    }
}

TEST_CASE("the model holds the body's voxels and links, not its workspace's cells") {
    const BodySpec s = sparse_body(true);
    const auto small = Model::build(s);
    const auto big = Model::build(embedded(s, {40, 40, 40}, {20, 30, 10}));
    // Links counted independently from the lattice: pairs of occupied face neighbours.
    int links = 0, voxels = 0;
    for (int z = 0; z < s.nz; ++z)
        for (int y = 0; y < s.ny; ++y)
            for (int x = 0; x < s.nx; ++x) {
                if (s.material[s.cell_index(x, y, z)] == 0) continue;
                ++voxels;
                links += x + 1 < s.nx && s.material[s.cell_index(x + 1, y, z)] != 0;
                links += y + 1 < s.ny && s.material[s.cell_index(x, y + 1, z)] != 0;
                links += z + 1 < s.nz && s.material[s.cell_index(x, y, z + 1)] != 0;
            }
    CHECK(small->voxel_count() == voxels);
    CHECK(small->link_count() == links);
    CHECK(big->voxel_count() == voxels);
    CHECK(big->link_count() == links);
    // Public voxel indices stay lattice order of the occupied cells of the spec's own lattice.
    for (int v = 0; v < big->voxel_count(); ++v) {
        const auto c = big->voxel_coords(v), d = small->voxel_coords(v);
        CHECK(c == std::array<int, 3>{d[0] + 20, d[1] + 30, d[2] + 10});
        CHECK(big->voxel_cell(v) == big->spec().cell_index(c[0], c[1], c[2]));
        if (v > 0) CHECK(big->voxel_cell(v) > big->voxel_cell(v - 1));
    }
    // A body's start state is its lattice points in world coordinates.
    World w(big);
    const double L = s.voxel_size_m;
    for (int v = 0; v < big->voxel_count(); ++v) {
        const auto c = big->voxel_coords(v);
        const auto p = w.voxel_position_m(v);
        for (int k = 0; k < 3; ++k)
            CHECK(p[k] == bhm::test::relative((c[k] + 0.5) * L, 1e-12));
    }
}
