// The CPU side of the renderer: a scene becomes the right instances, colours, lines and markers.
#include <doctest/doctest.h>

#include <algorithm>
#include <set>

#include "render/draw_list.hpp"
#include "render/face_culling.hpp"
#include "tests/render/render_fixtures.hpp"

using namespace bhm::render;
using namespace bhm::render::testing;

namespace {

std::vector<BoxInstance> body_boxes(const DrawList& list) {
    std::vector<BoxInstance> all;
    for (const auto* group : {&list.boxes, &list.translucent_boxes})
        for (const auto& b : *group)
            if ((static_cast<unsigned>(b.flags) & kBoxGhost) == 0) all.push_back(b);
    return all;
}

const BoxInstance& box_of_voxel(const DrawList& list, int v) {
    for (const auto* group : {&list.boxes, &list.translucent_boxes})
        for (const auto& b : *group)
            if (static_cast<int>(b.voxel) == v && (static_cast<unsigned>(b.flags) & kBoxGhost) == 0)
                return b;
    throw std::runtime_error("no box for voxel " + std::to_string(v));
}

int count_with_color(const std::vector<TriangleVertex>& vertices, glm::vec4 color) {
    return static_cast<int>(
        std::count_if(vertices.begin(), vertices.end(),
                      [&](const TriangleVertex& t) { return t.color == color; }));
}

// A straight row of n voxels along x, at rest.
Scene row_scene(int n) {
    bhm::engine::BodySpec spec;
    spec.nx = n, spec.ny = 1, spec.nz = 1;
    spec.material.assign(static_cast<std::size_t>(n), kPassive);
    Scene scene;
    scene.body = body_view_from_spec(spec);
    scene.material_colors = {palette::kActive, palette::kPassive, palette::kEnclosure};
    return scene;
}

}  // namespace

TEST_CASE("one instance per voxel, coloured by its material, held voxels flagged") {
    const Scene scene = mixed_scene();
    const auto spec = mixed_body_spec();
    const int filled = static_cast<int>(std::count_if(spec.material.begin(), spec.material.end(),
                                                      [](std::uint8_t m) { return m != 0; }));
    REQUIRE(filled == 6 * 4 * 3 - 3 - 1);  // notch of 3 and one hole
    const DrawList list = build_draw_list(scene);
    CHECK(list.voxel_instance_count() == filled);
    CHECK(list.boxes.size() == static_cast<std::size_t>(filled));  // all opaque
    CHECK(list.translucent_boxes.empty());

    std::set<int> seen;
    for (const auto& box : body_boxes(list)) {
        const int v = static_cast<int>(box.voxel);
        seen.insert(v);
        const auto c = scene.body.voxel_coords(v);
        const bool active = c[2] == 2 || (c[0] + c[1]) % 3 == 0;
        CHECK(box.color == (active ? palette::kActive : palette::kPassive));
        const bool held = c[0] == 0;
        CHECK(((static_cast<unsigned>(box.flags) & kBoxFixed) != 0) == held);
        // At rest: lattice position, unit orientation, full size.
        CHECK(box.centre.x == doctest::Approx((c[0] + 0.5) * 0.01).epsilon(1e-6));
        CHECK(box.centre.y == doctest::Approx((c[1] + 0.5) * 0.01).epsilon(1e-6));
        CHECK(box.centre.z == doctest::Approx((c[2] + 0.5) * 0.01).epsilon(1e-6));
        CHECK(box.orientation == glm::vec4(1, 0, 0, 0));
        CHECK(box.size == glm::vec3(0.01f));
    }
    CHECK(static_cast<int>(seen.size()) == filled);
}

TEST_CASE("translucent materials go to the translucent list, unknown materials show magenta") {
    Scene scene = row_scene(3);
    scene.body.voxel_material = {kEnclosure, kPassive, 9};
    const DrawList list = build_draw_list(scene);
    REQUIRE(list.translucent_boxes.size() == 1);
    CHECK(list.translucent_boxes[0].voxel == 0.0f);
    CHECK(list.translucent_boxes[0].color == palette::kEnclosure);
    CHECK(box_of_voxel(list, 2).color == palette::kUnknownMaterial);
}

TEST_CASE("front section hides exactly the voxels with lattice y above the cut") {
    Scene scene = mixed_scene();
    for (int cut : {0, 1, 2, 3}) {
        scene.options.section_y = cut;
        const DrawList list = build_draw_list(scene);
        int expected = 0;
        for (int v = 0; v < scene.body.voxel_count(); ++v)
            expected += scene.body.voxel_coords(v)[1] <= cut;
        CHECK(list.voxel_instance_count() == expected);
        for (const auto& box : body_boxes(list))
            CHECK(scene.body.voxel_coords(static_cast<int>(box.voxel))[1] <= cut);
        // The cut face of the remaining voxels is drawn: the +y face of every voxel at y = cut.
        for (const auto& box : body_boxes(list))
            if (scene.body.voxel_coords(static_cast<int>(box.voxel))[1] == cut && cut < 3)
                CHECK((static_cast<unsigned>(box.faces) & (1u << 3)) != 0);
    }
    scene.options.section_y = -1;
    CHECK(build_draw_list(scene).voxel_instance_count() == scene.body.voxel_count());
}

TEST_CASE("boundary faces are green when fixed, purple when free, absent otherwise") {
    Scene scene = mixed_scene();  // x- fixed, x+ free, the rest unmarked
    DrawList list = build_draw_list(scene);
    REQUIRE(list.translucent_triangles.size() == 12);  // two quads
    CHECK(count_with_color(list.translucent_triangles, palette::kFixedFace) == 6);
    CHECK(count_with_color(list.translucent_triangles, palette::kFreeFace) == 6);
    // The fixed quad lies on x = 0, the free one on x = workspace width (8 voxels).
    for (const auto& t : list.translucent_triangles) {
        if (t.color == palette::kFixedFace) CHECK(t.position.x == 0.0f);
        if (t.color == palette::kFreeFace) CHECK(t.position.x == doctest::Approx(0.08));
    }
    scene.faces = {FaceMarking::None,  FaceMarking::None, FaceMarking::Fixed,
                   FaceMarking::Fixed, FaceMarking::None, FaceMarking::Free};
    list = build_draw_list(scene);
    CHECK(count_with_color(list.translucent_triangles, palette::kFixedFace) == 12);
    CHECK(count_with_color(list.translucent_triangles, palette::kFreeFace) == 6);
    for (const auto& t : list.translucent_triangles)
        if (t.color == palette::kFreeFace) CHECK(t.position.z == doctest::Approx(0.04));
    scene.options.show_boundary_faces = false;
    CHECK(build_draw_list(scene).translucent_triangles.empty());
}

TEST_CASE("star on the (0,0,0) voxel, following it when the body moves") {
    Scene scene = mixed_scene();
    DrawList list = build_draw_list(scene);
    REQUIRE(list.markers.size() == 1);
    CHECK(list.markers[0].color == palette::kStar);
    CHECK(list.markers[0].position.x == doctest::Approx(0.005));
    CHECK(list.markers[0].position.y == doctest::Approx(0.005));
    CHECK(list.markers[0].position.z == doctest::Approx(0.005));
    // Voxel in cell 0 moved: the star goes with it.
    scene.body.poses.position_m[0] += 0.02f;
    list = build_draw_list(scene);
    CHECK(list.markers[0].position.x == doctest::Approx(0.025));
    // No voxel in cell 0: the star marks the cell's rest centre.
    scene = row_scene(3);
    scene.body.voxel_cell = {1, 2, 0};
    scene.body.voxel_cell.pop_back();
    scene.body.voxel_material.pop_back();
    scene.body.voxel_fixed.pop_back();
    scene.body.poses = rest_poses(scene.body);
    list = build_draw_list(scene);
    CHECK(list.markers[0].position.x == doctest::Approx(0.005));
}

TEST_CASE("workspace box, floor grid and framing bounds") {
    const Scene scene = mixed_scene();
    const DrawList list = build_draw_list(scene);
    CHECK(list.workspace_bounds.min == glm::vec3(0.0f));
    CHECK(list.workspace_bounds.max.x == doctest::Approx(0.08));
    CHECK(list.workspace_bounds.max.y == doctest::Approx(0.05));
    CHECK(list.workspace_bounds.max.z == doctest::Approx(0.04));
    // 12 box edges + 4 outline edges for each of the two marked faces, as line pairs.
    CHECK(list.lines.size() == 2 * (12 + 8));
    // Grid: workspace 8 x 5 plus two voxels of margin each side, lines at every voxel.
    CHECK(list.floor_lines.size() == 2 * ((12 + 1) + (9 + 1)));
    for (const auto& v : list.floor_lines)
        CHECK(v.position.z == 0.0f);
    CHECK(list.floor.size() == 6);
    CHECK(list.axes_gizmo);
    CHECK_FALSE(list.legend);
}

TEST_CASE("interior voxels and faces shared with meeting neighbours are not drawn") {
    bhm::engine::BodySpec spec;
    spec.nx = spec.ny = spec.nz = 3;
    spec.material.assign(27, kPassive);
    Scene scene;
    scene.body = body_view_from_spec(spec);
    scene.material_colors = {palette::kActive, palette::kPassive};
    DrawList list = build_draw_list(scene);
    REQUIRE(list.voxel_instance_count() == 27);
    int drawn_faces = 0;
    for (const auto& box : list.boxes) {
        const auto c = scene.body.voxel_coords(static_cast<int>(box.voxel));
        const unsigned faces = static_cast<unsigned>(box.faces);
        if (c == std::array<int, 3>{1, 1, 1}) CHECK(faces == 0u);
        // Exactly the faces on the block's outside remain.
        for (int f = 0; f < 6; ++f) {
            const int axis = f / 2;
            const bool outside = (f % 2) ? c[static_cast<std::size_t>(axis)] == 2
                                         : c[static_cast<std::size_t>(axis)] == 0;
            CHECK(((faces >> f) & 1u) == (outside ? 1u : 0u));
            drawn_faces += (faces >> f) & 1u;
        }
    }
    CHECK(drawn_faces == 6 * 9);

    // Turning one corner voxel by 0.2 rad opens gaps: its shared faces and its neighbours'
    // facing faces are drawn again.
    const float angle = 0.2f;
    scene.body.poses.orientation[0] = std::cos(0.5f * angle);
    scene.body.poses.orientation[3] = std::sin(0.5f * angle);
    list = build_draw_list(scene);
    const auto faces_of = [&](int v) { return static_cast<unsigned>(box_of_voxel(list, v).faces); };
    CHECK(faces_of(0) == 63u);
    CHECK((faces_of(1) & 1u) == 1u);    // x- of the voxel beside it
    CHECK((faces_of(3) & 4u) == 4u);    // y- of the voxel behind it
    CHECK((faces_of(9) & 16u) == 16u);  // z- of the voxel above it
    CHECK((faces_of(2) & 1u) == 0u);    // far from the turned voxel: still hidden
}

TEST_CASE("culling never hides an opaque face behind a translucent neighbour") {
    Scene scene = row_scene(2);
    scene.body.voxel_material = {kPassive, kEnclosure};
    const DrawList list = build_draw_list(scene);
    CHECK((static_cast<unsigned>(box_of_voxel(list, 0).faces) & 2u) == 2u);  // opaque x+ stays
    CHECK((static_cast<unsigned>(box_of_voxel(list, 1).faces) & 1u) == 0u);  // translucent x- goes
}

TEST_CASE("box corners follow position, orientation and size") {
    BoxInstance box;
    box.centre = {1, 2, 3};
    box.size = {0.2f, 0.4f, 0.6f};
    // 90 degrees about z: local +x goes to world +y.
    box.orientation = {std::cos(0.25f * 3.14159265f), 0, 0, std::sin(0.25f * 3.14159265f)};
    const glm::vec3 c = box_corner(box, 1, 1, 1);
    CHECK(c.x == doctest::Approx(1.0 - 0.2));
    CHECK(c.y == doctest::Approx(2.0 + 0.1));
    CHECK(c.z == doctest::Approx(3.0 + 0.3));
}

TEST_CASE("scalar colouring maps each voxel's value through the colour map and adds a legend") {
    Scene scene = row_scene(3);
    scene.options.color_mode = ColorMode::Scalar;
    scene.options.voxel_scalar = {0.0f, 5.0f, 20.0f};
    scene.options.scalar_range = {0.0f, 10.0f};
    const DrawList list = build_draw_list(scene);
    CHECK(box_of_voxel(list, 0).color == sample_color_map(ColorMapName::Sequential, 0.0f));
    CHECK(box_of_voxel(list, 1).color == sample_color_map(ColorMapName::Sequential, 0.5f));
    CHECK(box_of_voxel(list, 2).color ==
          sample_color_map(ColorMapName::Sequential, 1.0f));  // clamped
    REQUIRE(list.legend);
    CHECK(list.legend->range.max == 10.0f);
    // A voxel without the field (a passive voxel's fibre axis) keeps its material colour.
    scene.options.voxel_without_scalar = {0, 1, 0};
    const DrawList partial = build_draw_list(scene);
    CHECK(box_of_voxel(partial, 0).color == sample_color_map(ColorMapName::Sequential, 0.0f));
    CHECK(box_of_voxel(partial, 1).color == box_of_voxel(build_draw_list(row_scene(3)), 1).color);
    CHECK(box_of_voxel(partial, 1).color != sample_color_map(ColorMapName::Sequential, 0.5f));
    scene.options.voxel_without_scalar.pop_back();
    CHECK_THROWS_WITH_AS(build_draw_list(scene),
                         doctest::Contains("voxel_without_scalar has 2 flags"),
                         std::invalid_argument);
    scene.options.voxel_without_scalar.clear();
    scene.options.voxel_scalar.pop_back();
    CHECK_THROWS_WITH_AS(build_draw_list(scene), doctest::Contains("voxel_scalar has 2 values"),
                         std::invalid_argument);
}

TEST_CASE("ghost of t = 0: translucent, offset, not counted as body voxels") {
    Scene scene = mixed_scene();
    scene.ghost_poses = scene.body.poses;
    scene.body.poses = curled_poses(scene.body);
    scene.options.show_ghost = true;
    scene.options.ghost_offset_m = {0.0f, 0.1f, 0.0f};
    const DrawList list = build_draw_list(scene);
    CHECK(list.voxel_instance_count() == scene.body.voxel_count());
    int ghosts = 0;
    for (const auto& b : list.translucent_boxes) {
        if ((static_cast<unsigned>(b.flags) & kBoxGhost) == 0) continue;
        ++ghosts;
        CHECK(b.color == palette::kGhost);
        const auto c = scene.body.voxel_coords(static_cast<int>(b.voxel));
        CHECK(b.centre.y == doctest::Approx((c[1] + 0.5) * 0.01 + 0.1).epsilon(1e-5));
    }
    CHECK(ghosts == scene.body.voxel_count());
    CHECK(list.bounds.max.y >= 0.1f + 0.04f - 1e-4f);  // framing includes the ghost beside
}

TEST_CASE("centre-of-mass trail: a polyline drawn over the body, a dot at its end") {
    Scene scene = row_scene(2);
    scene.options.com_trail_m = {{0, 0, 0}, {0.01f, 0, 0}, {0.02f, 0.01f, 0}};
    const DrawList list = build_draw_list(scene);
    REQUIRE(list.lines_on_top.size() == 4);  // two segments
    for (const auto& v : list.lines_on_top)
        CHECK(v.color == palette::kComTrail);
    CHECK(list.lines_on_top[3].position == glm::vec3(0.02f, 0.01f, 0.0f));
    REQUIRE(list.markers.size() == 2);  // the star and the dot
    const auto dot = std::find_if(list.markers.begin(), list.markers.end(),
                                  [](const Marker& m) { return m.shape == MarkerShape::Dot; });
    REQUIRE(dot != list.markers.end());
    CHECK(dot->position == glm::vec3(0.02f, 0.01f, 0.0f));
}

TEST_CASE("inconsistent scenes are refused with a clear reason") {
    Scene scene = row_scene(3);
    scene.body.poses.position_m.resize(6);
    CHECK_THROWS_WITH_AS(build_draw_list(scene),
                         doctest::Contains("poses hold 2 voxels, the body has 3"),
                         std::invalid_argument);
    scene = row_scene(3);
    scene.body.voxel_cell[1] = 7;
    CHECK_THROWS_WITH_AS(build_draw_list(scene), doctest::Contains("outside the 3x1x1 lattice"),
                         std::invalid_argument);
}

TEST_CASE("an empty body still gives a workspace to frame and draw") {
    Scene scene;
    scene.body.nx = 4, scene.body.ny = 4, scene.body.nz = 4;
    const DrawList list = build_draw_list(scene);
    CHECK(list.voxel_instance_count() == 0);
    CHECK(list.bounds.valid);
    CHECK(list.bounds.max.x == doctest::Approx(0.04));
    CHECK(list.markers.size() == 1);
}
