// Picking in the 3D view against geometry worked out by hand: a camera straight above the
// workspace, one looking along -x, and the lattice walk against a brute-force ray/box test.
#include <doctest/doctest.h>

#include <cmath>
#include <set>

#include "app/gui/view/picking.hpp"

using namespace bhm;
using namespace bhm::app::gui;

namespace {

// Orthographic camera straight down on the centre of a 4 x 2 x 3 workspace of 1 cm voxels,
// showing 4 cm vertically (half height 2 cm) in a 400 x 400 viewport: 100 px per cm.
render::Camera top_camera() {
    render::Camera c;
    c.target = {0.02f, 0.01f, 0.015f};
    c.yaw_rad = -0.5f * 3.14159265f;  // right = +x, up = +y (render::NamedView::Top)
    c.pitch_rad = 0.5f * 3.14159265f;
    c.orthographic = true;
    c.fov_y_rad = 0.6f;
    c.distance_m = 0.02f / std::tan(0.3f);  // half height = distance x tan(fov/2)
    c.scene_radius_m = 0.05f;
    return c;
}

const LatticeBox kBox{{4, 2, 3}, 0.01};

}  // namespace

TEST_CASE("studio picking: a pixel projects and unprojects onto the same world point") {
    const auto camera = top_camera();
    const glm::vec2 viewport{400.0f, 400.0f};
    REQUIRE(std::abs(camera.half_height_m() - 0.02f) < 1e-6f);
    // The centre of the viewport is the target; 100 px per cm, +x right, +y up the screen.
    const auto centre = project_to_pixel(camera, camera.target, viewport);
    REQUIRE(centre);
    CHECK(centre->x == doctest::Approx(200.0f).epsilon(1e-4));
    CHECK(centre->y == doctest::Approx(200.0f).epsilon(1e-4));
    const auto corner = project_to_pixel(camera, {0.0f, 0.0f, 0.03f}, viewport);
    REQUIRE(corner);
    CHECK(corner->x == doctest::Approx(0.0f).epsilon(1e-3));
    CHECK(corner->y == doctest::Approx(300.0f).epsilon(1e-4));  // y = 0 is 1 cm below the target
    const Ray ray = ray_through_pixel(camera, *corner, viewport);
    CHECK(ray.direction.z == doctest::Approx(-1.0f).epsilon(1e-5));
    CHECK(ray.origin.x == doctest::Approx(0.0f).epsilon(1e-4));
    CHECK(ray.origin.y == doctest::Approx(0.0f).epsilon(1e-4));
}

TEST_CASE(
    "studio picking: looking down, the ray enters through z+ and the cell under it is on top") {
    const auto camera = top_camera();
    const glm::vec2 viewport{400.0f, 400.0f};
    // Pixel (250, 150): x = 2.5 cm, y = 1.5 cm -> cell (2, 1, top layer 2).
    const Ray ray = ray_through_pixel(camera, {250.0f, 150.0f}, viewport);
    const auto face = pick_box_face(ray, kBox);
    REQUIRE(face);
    CHECK(face->face == evo::Face::ZMax);
    CHECK(face->point_m.x == doctest::Approx(0.025f).epsilon(1e-4));
    CHECK(face->point_m.z == doctest::Approx(0.03f).epsilon(1e-4));

    const auto nothing = [](const std::array<int, 3>&) { return false; };
    auto cell = pick_cell(ray, kBox, {}, nothing);
    REQUIRE(cell);
    CHECK(cell->cell == std::array<int, 3>{2, 1, 2});
    CHECK_FALSE(cell->occupied);

    // An occupied cell lower down is found when the ones above are empty.
    const auto bottom_only = [](const std::array<int, 3>& c) { return c[2] == 0; };
    cell = pick_cell(ray, kBox, {}, bottom_only);
    REQUIRE(cell);
    CHECK(cell->cell == std::array<int, 3>{2, 1, 0});
    CHECK(cell->occupied);

    // A slice at z = 1 hides the top layer: the fallback is the slice's top layer.
    cell = pick_cell(ray, kBox, Slice{2, 1}, nothing);
    REQUIRE(cell);
    CHECK(cell->cell == std::array<int, 3>{2, 1, 1});

    // Outside the workspace's footprint: no face, no cell.
    const Ray miss = ray_through_pixel(camera, {10.0f, 10.0f}, viewport);
    CHECK_FALSE(pick_box_face(miss, kBox));
    CHECK_FALSE(pick_cell(miss, kBox, {}, nothing));
}

TEST_CASE(
    "studio picking: every face is the entry face of a ray aimed at its centre from outside") {
    for (int f = 0; f < 6; ++f) {
        const auto face = static_cast<evo::Face>(f);
        const glm::vec3 centre = face_centre_m(kBox, face);
        glm::vec3 normal(0.0f);
        normal[f / 2] = (f % 2) ? 1.0f : -1.0f;
        const Ray ray{centre + 0.1f * normal + glm::vec3(0.001f, 0.0007f, 0.0003f), -normal};
        const auto hit = pick_box_face(ray, kBox);
        REQUIRE(hit);
        CHECK(hit->face == face);
        CHECK(hit->distance_m == doctest::Approx(0.1f).epsilon(0.02));
    }
    // A ray starting inside the box enters through no face.
    CHECK_FALSE(pick_box_face(Ray{{0.02f, 0.01f, 0.01f}, {1.0f, 0.0f, 0.0f}}, kBox));
}

TEST_CASE("studio picking: the lattice walk visits exactly the cells a dense ray sample crosses") {
    const glm::vec3 origin{-0.013f, -0.004f, 0.041f};
    const glm::vec3 direction = glm::normalize(glm::vec3{0.05f, 0.021f, -0.037f});
    std::vector<std::array<int, 3>> walked;
    walk_cells({origin, direction}, kBox, [&](const std::array<int, 3>& c) {
        walked.push_back(c);
        return true;
    });
    // Brute force: sample the ray every 10 um and collect the cells in order.
    std::vector<std::array<int, 3>> sampled;
    for (float t = 0.0f; t < 0.2f; t += 1e-5f) {
        const glm::vec3 p = origin + t * direction;
        const std::array<int, 3> c{static_cast<int>(std::floor(p.x / 0.01f)),
                                   static_cast<int>(std::floor(p.y / 0.01f)),
                                   static_cast<int>(std::floor(p.z / 0.01f))};
        if (kBox.contains_cell(c) && (sampled.empty() || sampled.back() != c)) sampled.push_back(c);
    }
    REQUIRE(sampled.size() >= 4);
    CHECK(walked == sampled);
}

TEST_CASE("studio picking: a replayed voxel is hit as the oriented box it is drawn as") {
    // A 1 cm voxel at the origin; rays along +x at heights worked out by hand.
    const float axis_aligned[4] = {1.0f, 0.0f, 0.0f, 0.0f};
    const float s = std::sqrt(0.5f);
    const float turned_90_about_z[4] = {s, 0.0f, 0.0f, s};  // cos 45, sin 45: 90 degrees
    const glm::vec3 cube{0.01f, 0.01f, 0.01f};
    Ray ray;
    ray.origin = {-1.0f, 0.0065f, 0.0f};
    ray.direction = {1.0f, 0.0f, 0.0f};
    // Axis-aligned, the half edge is 5 mm: a ray 6.5 mm off the axis misses.
    CHECK_FALSE(ray_box_distance(ray, {0, 0, 0}, axis_aligned, cube));
    // 90 degrees about z: the same cube, still missed; a box long along its own x is long along y.
    CHECK_FALSE(ray_box_distance(ray, {0, 0, 0}, turned_90_about_z, cube));
    const glm::vec3 long_x{0.02f, 0.01f, 0.01f};  // 2 cm along its own x, which now points along y
    const auto hit = ray_box_distance(ray, {0, 0, 0}, turned_90_about_z, long_x);
    REQUIRE(hit);
    CHECK(*hit == doctest::Approx(1.0f - 0.005f).epsilon(1e-4));  // enters its 1 cm wide side
    // 45 degrees about z: the half diagonal, 7.07 mm, reaches the ray.
    const float c = std::cos(0.5f * 0.7853982f), sn = std::sin(0.5f * 0.7853982f);
    const float turned[4] = {c, 0.0f, 0.0f, sn};
    const auto diagonal = ray_box_distance(ray, {0, 0, 0}, turned, cube);
    REQUIRE(diagonal);
    // The faces at 45 degrees: x + y = 7.07 mm on the near side, so x = -(7.07 - 6.5) mm.
    CHECK(*diagonal == doctest::Approx(1.0f - (0.0070711f - 0.0065f)).epsilon(1e-4));

    // Two voxels one behind the other along the ray: the nearer one is picked.
    engine::VoxelPoses poses;
    poses.position_m = {0.03f, 0.0f, 0.0f, 0.01f, 0.0f, 0.0f};
    poses.orientation = {1, 0, 0, 0, 1, 0, 0, 0};
    poses.size_m = {0.01f, 0.01f, 0.01f, 0.01f, 0.01f, 0.01f};
    Ray along;
    along.origin = {-1.0f, 0.001f, 0.002f};
    along.direction = {1.0f, 0.0f, 0.0f};
    const auto first = pick_posed_voxel(along, poses);
    REQUIRE(first);
    CHECK(first->voxel == 1);
    CHECK(first->distance_m == doctest::Approx(1.005f).epsilon(1e-4));
    along.origin.y = 0.02f;
    CHECK_FALSE(pick_posed_voxel(along, poses));
}
