// bhm verify's FEM meshes the body our engine simulates: voxels joined by a face share their
// nodes, voxels that only touch along an edge or at a corner do not (evo/verify/fem_model.cpp,
// docs/verify.md "Edge and corner contacts"). Before, one node per grid point welded them, and a
// champion of paper-exp1-attached whose far lobe touched its held root along a few edges read
// "differs by 197 %": the FEM's edges carried load that neither our engine nor the continuum's
// limit carries.
#include <doctest/doctest.h>

#include "support/ccx_skip.hpp"

#include <cmath>

#include "evo/verify/fem_model.hpp"
#include "evo/verify/verify_body.hpp"

using namespace bhm;

namespace {

using bhm::test::skip_without_ccx;

engine::BodySpec box(int nx, int ny, int nz) {
    engine::BodySpec s;
    s.nx = nx;
    s.ny = ny;
    s.nz = nz;
    s.voxel_size_m = 0.01;
    engine::Material m;
    m.youngs_modulus_pa = 5e6;
    m.poisson_ratio = 0.35;
    s.materials = {m};
    s.material.assign(static_cast<std::size_t>(s.cell_count()), 0);
    s.fixed.assign(static_cast<std::size_t>(s.cell_count()), 0);
    return s;
}

void fill(engine::BodySpec& s, int x, int y, int z, bool held = false) {
    s.material[static_cast<std::size_t>(s.cell_index(x, y, z))] = 1;
    s.fixed[static_cast<std::size_t>(s.cell_index(x, y, z))] = held ? 1 : 0;
}

int nodes_of(const engine::BodySpec& s, evo::FemElement element, int subdivision) {
    return evo::build_fem_model(s, {element, subdivision}).node_count();
}

// A U of 1x1 bars in the xz plane, held at its x = 0 end: the lower bar x 0..4 at z = 0, a post at
// x = 4, the upper bar x 1..4 at z = 2, hanging free at x = 1. With `stub`, a held voxel at
// (0, 0, 3), alone, which touches the upper bar's free end (1, 0, 2) along one edge only.
engine::BodySpec hook(bool stub) {
    auto s = box(5, 1, 4);
    for (int x = 0; x < 5; ++x)
        fill(s, x, 0, 0, x == 0);
    fill(s, 4, 0, 1);
    for (int x = 1; x < 5; ++x)
        fill(s, x, 0, 2);
    if (stub) fill(s, 0, 0, 3, true);
    s.environment.gravity_m_s2 = -9.81;
    return s;
}

}  // namespace

TEST_CASE("verify contacts: voxels touching along an edge or at a corner get nodes of their own") {
    for (const auto element : {evo::FemElement::C3D8I, evo::FemElement::C3D20R}) {
        CAPTURE(evo::fem_element_name(element));
        const bool quadratic = element == evo::FemElement::C3D20R;
        const int voxel = quadratic ? 20 : 8;  // one element per voxel
        const int face = quadratic ? 8 : 4;    // nodes on a shared face
        // Two voxels on a diagonal of a 2x2x1 box touch along one edge: nothing shared.
        auto edge = box(2, 2, 1);
        fill(edge, 0, 0, 0, true);
        fill(edge, 1, 1, 0);
        CHECK(nodes_of(edge, element, 1) == 2 * voxel);
        // Joined by a third voxel beside both, the edge is inside the body's material: an L of
        // three voxels has two shared faces and the edge's nodes once.
        auto joined = edge;
        fill(joined, 1, 0, 0);
        CHECK(nodes_of(joined, element, 1) == 3 * voxel - 2 * face);
        // Two voxels on the body diagonal of a 2x2x2 box touch at one point: nothing shared.
        auto corner = box(2, 2, 2);
        fill(corner, 0, 0, 0, true);
        fill(corner, 1, 1, 1);
        CHECK(nodes_of(corner, element, 1) == 2 * voxel);
        // A full 2x2x2 block keeps one structured grid: (2 s + 1)^3 points for C3D8I at s = 2.
        if (!quadratic) {
            auto block = box(2, 2, 2);
            for (int z = 0; z < 2; ++z)
                for (int y = 0; y < 2; ++y)
                    for (int x = 0; x < 2; ++x)
                        fill(block, x, y, z, x == 0);
            CHECK(nodes_of(block, element, 2) == 5 * 5 * 5);
        }
    }
}

TEST_CASE("verify contacts: a held voxel touching a free bar along one edge does not hold it") {
    if (skip_without_ccx()) return;
    // The truth: a voxel that meets the body along an edge only carries nothing in our engine
    // (no link, no edge spring without the voxels between) nor in the continuum's limit, so the
    // hook sags the same with and without the held stub beside its free end. With the stub
    // welded at the shared edge (one node per grid point, before), the U became a closed frame.
    evo::VerifyOptions options;
    const evo::FemMeshOptions mesh{evo::FemElement::C3D20R, 2};
    const auto open = evo::solve_fem(hook(false), mesh, false, options);
    const auto touched = evo::solve_fem(hook(true), mesh, false, options);
    REQUIRE(!open.loads.empty());
    REQUIRE(!touched.loads.empty());
    const double free_sag = open.loads[0].fem_largest_m;
    const double touched_sag = touched.loads[0].fem_largest_m;
    MESSAGE("largest voxel displacement at rest: " << free_sag * 1e3 << " mm open, "
                                                   << touched_sag * 1e3 << " mm with the stub");
    // The stub's own 8 nodes (C3D8I, one element per voxel), none shared with the bar.
    CHECK(nodes_of(hook(true), evo::FemElement::C3D8I, 1) ==
          nodes_of(hook(false), evo::FemElement::C3D8I, 1) + 8);
    CHECK(free_sag > 0.0);
    CHECK(std::abs(touched_sag / free_sag - 1.0) < 0.01);
}
