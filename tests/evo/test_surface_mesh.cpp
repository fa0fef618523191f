// Surface meshes of voxel bodies: closed, outward, the right volume at rest and under rigid
// motion, voxels touching only along an edge or a corner kept apart, STL/OBJ encodings.
#include <doctest/doctest.h>

#include <algorithm>
#include <bit>
#include <cmath>
#include <cstring>
#include <numbers>
#include <set>
#include <sstream>

#include "evo/formats/surface_mesh.hpp"
#include "evo_test_support.hpp"
#include "mesh_check.hpp"

using namespace bhm;
using namespace bhm::evo;

namespace {

void check_closed(const SurfaceMesh& mesh) {
    const auto topology = bhm::test::check_topology(mesh.triangles);
    CHECK(topology.edges > 0);
    CHECK(topology.edges_not_in_two == 0);
    CHECK(topology.directed_edges_repeated == 0);
    // Euler characteristic of closed surfaces: V - E + F = 2 per sphere-like component (even).
    const int chi = static_cast<int>(mesh.vertices.size()) - topology.edges +
                    static_cast<int>(mesh.triangles.size());
    CHECK(chi % 2 == 0);
}

// A replay of the cells at rest, to be moved by the tests.
engine::Replay replay_of(const std::array<int, 3>& n, const std::vector<std::uint8_t>& cells,
                         double L) {
    engine::Replay replay;
    replay.nx = n[0];
    replay.ny = n[1];
    replay.nz = n[2];
    replay.voxel_size_m = L;
    engine::VoxelPoses frame;
    for (int c = 0; c < static_cast<int>(cells.size()); ++c) {
        if (!cells[c]) continue;
        replay.voxel_cell.push_back(c);
        replay.voxel_material.push_back(cells[c]);
        replay.voxel_fixed.push_back(0);
        const int xyz[3] = {c % n[0], (c / n[0]) % n[1], c / (n[0] * n[1])};
        for (int a = 0; a < 3; ++a) {
            frame.position_m.push_back(static_cast<float>((xyz[a] + 0.5) * L));
            frame.size_m.push_back(static_cast<float>(L));
        }
        frame.orientation.insert(frame.orientation.end(), {1.0f, 0.0f, 0.0f, 0.0f});
    }
    replay.frames.push_back(frame);
    return replay;
}

}  // namespace

TEST_CASE("one voxel: 12 outward triangles, 8 vertices, volume L^3") {
    const auto mesh = rest_surface({1, 1, 1}, {2}, 0.01);
    CHECK(mesh.triangles.size() == 12);
    CHECK(mesh.vertices.size() == 8);
    check_closed(mesh);
    CHECK(bhm::test::signed_volume(mesh.vertices, mesh.triangles) ==
          doctest::Approx(1e-6).epsilon(1e-12));
    for (int m : mesh.triangle_material)
        CHECK(m == 2);
}

TEST_CASE("shared faces are removed: a 3x2x2 block has only its outer faces") {
    const auto mesh = rest_surface({3, 2, 2}, std::vector<std::uint8_t>(12, 1), 0.5);
    // Outer area in unit faces: 2 (3*2 + 3*2 + 2*2) = 32 quads.
    CHECK(mesh.triangles.size() == 64);
    CHECK(mesh.vertices.size() == 4 * 3 * 3 - 2 * 1 * 1);  // lattice points minus interior ones
    check_closed(mesh);
    CHECK(enclosed_volume(mesh) == doctest::Approx(12 * 0.125));
}

TEST_CASE("voxels touching only along an edge or at a corner stay two closed shells") {
    // Edge contact: (0,0,0) and (1,1,0). Corner contact: (0,0,0) and (1,1,1).
    for (const std::vector<std::uint8_t>& cells :
         {std::vector<std::uint8_t>{1, 0, 0, 1, 0, 0, 0, 0},
          std::vector<std::uint8_t>{1, 0, 0, 0, 0, 0, 0, 2}}) {
        const auto mesh = rest_surface({2, 2, 2}, cells, 1.0);
        CHECK(mesh.triangles.size() == 24);
        CHECK(mesh.vertices.size() == 16);  // the shared points are split, one per voxel
        check_closed(mesh);
        CHECK(enclosed_volume(mesh) == doctest::Approx(2.0));
    }
    // Six of eight cells around a point with the two empty ones diagonal: one shell, but the
    // centre point is split in two sheets, so edges still meet two triangles each.
    std::vector<std::uint8_t> cells(8, 1);
    cells[0] = 0;
    cells[7] = 0;
    const auto mesh = rest_surface({2, 2, 2}, cells, 1.0);
    check_closed(mesh);
    CHECK(enclosed_volume(mesh) == doctest::Approx(6.0));
}

TEST_CASE("a random body: closed and volume = voxels x L^3") {
    std::uint32_t state = 12345;
    const auto next = [&] {
        state = state * 1664525u + 1013904223u;
        return state >> 24;
    };
    // Fill fractions from 25% to 75%: many voxels touching only along edges or at corners.
    for (int trial = 0; trial < 150; ++trial) {
        const std::array<int, 3> n{5, 4, 3};
        std::vector<std::uint8_t> cells(60);
        int voxels = 0;
        const unsigned empty_in_four = 1 + trial % 3;
        for (auto& c : cells) {
            c = static_cast<std::uint8_t>(next() % 4 < empty_in_four ? 0 : 1 + next() % 3);
            voxels += c ? 1 : 0;
        }
        const auto mesh = rest_surface(n, cells, 0.01);
        check_closed(mesh);
        CHECK(enclosed_volume(mesh) == doctest::Approx(voxels * 1e-6).epsilon(1e-9));
        // Every triangle names a material of the palette; the surface area per material is
        // counted below against the faces of that material's voxels.
        std::set<int> used(mesh.triangle_material.begin(), mesh.triangle_material.end());
        CHECK(*used.begin() >= 1);
        CHECK(*used.rbegin() <= 3);
        std::array<int, 4> exposed{};
        for (int c = 0; c < 60; ++c) {
            if (!cells[c]) continue;
            const int x = c % 5, y = (c / 5) % 4, z = c / 20;
            for (int d = 0; d < 6; ++d) {
                int p[3] = {x, y, z};
                p[d / 2] += d % 2 ? 1 : -1;
                const bool inside =
                    p[0] >= 0 && p[1] >= 0 && p[2] >= 0 && p[0] < 5 && p[1] < 4 && p[2] < 3;
                if (!inside || !cells[p[0] + 5 * (p[1] + 4 * p[2])]) ++exposed[cells[c]];
            }
        }
        for (int m = 1; m <= 3; ++m)
            CHECK(std::count(mesh.triangle_material.begin(), mesh.triangle_material.end(), m) ==
                  2 * exposed[m]);
    }
}

TEST_CASE("deformed surface follows poses: rigid rotation keeps the volume, scaling scales it") {
    const std::array<int, 3> n{3, 2, 2};
    std::vector<std::uint8_t> cells{1, 1, 0, 1, 2, 2, 0, 1, 1, 2, 0, 0};
    const double L = 0.01;
    auto replay = replay_of(n, cells, L);
    const int voxels = static_cast<int>(replay.voxel_cell.size());
    {  // at rest the deformed mesh equals the rest mesh
        const auto rest = rest_surface(n, cells, L);
        const auto same = deformed_surface(replay, replay.frames[0]);
        REQUIRE(same.vertices.size() == rest.vertices.size());
        CHECK(same.triangles == rest.triangles);
        for (std::size_t v = 0; v < rest.vertices.size(); ++v)
            for (int a = 0; a < 3; ++a)
                CHECK(same.vertices[v][a] == doctest::Approx(rest.vertices[v][a]).epsilon(1e-6));
    }
    // Rotate the whole body 30 degrees about z around the origin: every voxel's centre and
    // orientation turn together.
    const double angle = std::numbers::pi / 6.0;
    engine::VoxelPoses turned = replay.frames[0];
    for (int v = 0; v < voxels; ++v) {
        const double x = turned.position_m[3 * v], y = turned.position_m[3 * v + 1];
        turned.position_m[3 * v] = static_cast<float>(std::cos(angle) * x - std::sin(angle) * y);
        turned.position_m[3 * v + 1] =
            static_cast<float>(std::sin(angle) * x + std::cos(angle) * y);
        const float q[4] = {static_cast<float>(std::cos(angle / 2)), 0.0f, 0.0f,
                            static_cast<float>(std::sin(angle / 2))};
        std::memcpy(&turned.orientation[4 * v], q, sizeof q);
    }
    const auto rotated = deformed_surface(replay, turned);
    check_closed(rotated);
    CHECK(enclosed_volume(rotated) == doctest::Approx(voxels * L * L * L).epsilon(1e-5));
    // The lattice origin (0,0,0) is a corner of voxel (0,0,0) alone and stays at the origin.
    bool origin_found = false;
    for (const auto& v : rotated.vertices)
        origin_found |= std::hypot(v[0], v[1], v[2]) < 1e-7;
    CHECK(origin_found);
    // Uniform 10% growth of every voxel about its centre with centres spread 10%: volume x 1.331.
    engine::VoxelPoses grown = replay.frames[0];
    for (auto& p : grown.position_m)
        p *= 1.1f;
    for (auto& s : grown.size_m)
        s *= 1.1f;
    CHECK(enclosed_volume(deformed_surface(replay, grown)) ==
          doctest::Approx(voxels * L * L * L * 1.331).epsilon(1e-5));
}

TEST_CASE("neighbours' corners are averaged, so a gap between voxels closes") {
    // Two voxels along x; the second one shifted +x by 2 mm: the shared face's corners sit
    // halfway, 1 mm beyond the rest position.
    std::vector<std::uint8_t> cells{1, 1};
    auto replay = replay_of({2, 1, 1}, cells, 0.01);
    replay.frames[0].position_m[3] += 0.002f;
    const auto mesh = deformed_surface(replay, replay.frames[0]);
    check_closed(mesh);
    int shared = 0;
    for (const auto& v : mesh.vertices)
        if (std::fabs(v[0] - 0.011) < 1e-6) ++shared;
    CHECK(shared == 4);
    CHECK(enclosed_volume(mesh) == doctest::Approx(2.2e-6).epsilon(1e-5));
}

TEST_CASE("STL: 84-byte header + 50 bytes per facet, unit outward normals") {
    const auto mesh = rest_surface({2, 1, 1}, {1, 1}, 0.01);
    const std::string stl = stl_binary(mesh);
    REQUIRE(stl.size() == 84 + 50 * mesh.triangles.size());
    std::uint32_t count = 0;
    for (int i = 0; i < 4; ++i)
        count |= static_cast<std::uint32_t>(static_cast<unsigned char>(stl[80 + i])) << (8 * i);
    CHECK(count == mesh.triangles.size());
    const auto f32 = [&](std::size_t at) {
        std::uint32_t bits = 0;
        for (int i = 0; i < 4; ++i)
            bits |= static_cast<std::uint32_t>(static_cast<unsigned char>(stl[at + i])) << (8 * i);
        return std::bit_cast<float>(bits);
    };
    double volume = 0.0;
    for (std::size_t t = 0; t < count; ++t) {
        const std::size_t at = 84 + 50 * t;
        const double normal[3] = {f32(at), f32(at + 4), f32(at + 8)};
        CHECK(std::hypot(normal[0], normal[1], normal[2]) == doctest::Approx(1.0));
        std::array<std::array<double, 3>, 3> p;
        for (int k = 0; k < 3; ++k)
            for (int a = 0; a < 3; ++a)
                p[k][a] = f32(at + 12 + 12 * k + 4 * a);
        // The normal points away from the body's centre (1 cm, 0.5 cm, 0.5 cm).
        const double centre[3] = {0.01, 0.005, 0.005};
        double outward = 0.0;
        for (int a = 0; a < 3; ++a)
            outward += normal[a] * ((p[0][a] + p[1][a] + p[2][a]) / 3.0 - centre[a]);
        CHECK(outward > 0.0);
        volume += bhm::test::signed_volume({p[0], p[1], p[2]}, {{0, 1, 2}});
    }
    CHECK(volume == doctest::Approx(2e-6).epsilon(1e-6));
}

TEST_CASE("OBJ: one group per material used, faces refer to written vertices") {
    auto e = bhm::evo::test::tiny_experiment({2, 1, 1});
    e.materials[0].name = "soft tissue";
    const auto mesh = rest_surface({2, 1, 1}, {1, 2}, 0.01);
    const std::string obj = obj_document(mesh, e.materials, "body.mtl");
    std::istringstream in(obj);
    std::string line;
    int vertices = 0, faces = 0;
    std::vector<std::string> groups;
    while (std::getline(in, line)) {
        if (line.rfind("v ", 0) == 0) ++vertices;
        if (line.rfind("f ", 0) == 0) ++faces;
        if (line.rfind("g ", 0) == 0) groups.push_back(line.substr(2));
    }
    CHECK(vertices == static_cast<int>(mesh.vertices.size()));
    CHECK(faces == 20);
    CHECK(groups == std::vector<std::string>{"soft_tissue", "active"});
    CHECK(obj.find("mtllib body.mtl") != std::string::npos);
    const std::string mtl = mtl_document(e.materials);
    CHECK(mtl.find("newmtl soft_tissue") != std::string::npos);
    CHECK(mtl.find("newmtl active") != std::string::npos);
    // Material indices beyond the palette are refused rather than silently dropped.
    const auto wide = rest_surface({1, 1, 1}, {3}, 0.01);
    CHECK_THROWS(obj_document(wide, e.materials, "x.mtl"));
}
