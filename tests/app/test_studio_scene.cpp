// What the 3D view draws, checked on the CPU: the painter's workspace scene (frame, overrides,
// slice), the cells picking treats as occupied, and the simulated body with hidden voxels culled.
#include <doctest/doctest.h>

#include <algorithm>

#include "app/gui/document/constraint_edits.hpp"
#include "app/gui/session/body_simulator.hpp"
#include "app/gui/shell/headless_studio.hpp"
#include "app/gui/view/scene.hpp"
#include "app/gui/view/viewport.hpp"
#include "render/image.hpp"
#include "test_studio_fixtures.hpp"

using namespace bhm;
using namespace bhm::app::gui;

namespace {

int count_material(const render::BodyView& body, int material) {
    return static_cast<int>(
        std::count(body.voxel_material.begin(), body.voxel_material.end(), material));
}

}  // namespace

TEST_CASE("studio scene: the painter shows the frame, the overrides and the slice") {
    auto e = testing::tiny_experiment({4, 3, 3});
    e = with_enclosure_thickness(e, evo::Face::XMin, 1);  // the x = 0 layer: 9 frame cells
    e = with_override(e, {2, 1, 1}, PaintKind::Empty);
    e = with_override(e, {3, 0, 0}, PaintKind::Fixed);
    e = with_override(e, {3, 2, 2}, PaintKind::Material, 2);
    const auto extra = painter_materials(e);
    CHECK(extra.frame == 3);
    CHECK(extra.forbidden == 4);
    CHECK(extra.fixed == 5);

    const PainterState painter;
    const auto scene = workspace_scene(e, painter, nullptr);
    const auto& body = scene.body;
    CHECK(body.voxel_count() == 9 + 3);
    CHECK(count_material(body, extra.frame) == 9);
    CHECK(count_material(body, extra.forbidden) == 1);
    CHECK(count_material(body, extra.fixed) == 1);
    CHECK(count_material(body, 2) == 1);
    for (int v = 0; v < body.voxel_count(); ++v) {
        const auto c = body.voxel_coords(v);
        const bool held = c == std::array<int, 3>{3, 0, 0};
        CHECK(body.voxel_fixed[static_cast<std::size_t>(v)] == (held ? 1 : 0));
    }
    CHECK(scene.faces[0] == render::FaceMarking::Fixed);
    CHECK(scene.faces[1] == render::FaceMarking::Free);
    REQUIRE(scene.material_colors.size() == 5);
    CHECK(scene.material_colors[2].a < 1.0f);  // the frame is see-through

    // The same cells are what picking stops at.
    const auto occupied = painter_occupancy(e, nullptr);
    CHECK(std::count(occupied.begin(), occupied.end(), 1) == 12);

    // A slice at z = 0 hides the two upper layers.
    PainterState sliced;
    sliced.slice = {2, 0};
    const auto low = workspace_scene(e, sliced, nullptr);
    CHECK(low.body.voxel_count() == 3 + 1);  // frame column at z = 0, the fixed marker
}

TEST_CASE("studio scene: a champion inside the workspace is shown under the frame") {
    auto e = testing::tiny_experiment({3, 2, 2});
    evo::Body champion;
    champion.size = {3, 2, 2};
    champion.cells.assign(12, 2);
    const auto scene = workspace_scene(e, PainterState{}, &champion);
    CHECK(scene.body.voxel_count() == 12);
    CHECK(count_material(scene.body, 2) == 12);
    evo::Body wrong_size = champion;
    wrong_size.size = {2, 3, 2};  // not this workspace: not drawn
    CHECK(workspace_scene(e, PainterState{}, &wrong_size).body.voxel_count() == 0);
}

TEST_CASE("studio scene: only voxels with an empty neighbour are drawn") {
    engine::Replay replay;
    replay.nx = replay.ny = replay.nz = 3;
    for (int cell = 0; cell < 27; ++cell) {
        replay.voxel_cell.push_back(cell);
        replay.voxel_material.push_back(1);
        replay.voxel_fixed.push_back(0);
    }
    const auto surface = surface_voxels(replay);
    CHECK(surface.size() == 26);
    CHECK(std::find(surface.begin(), surface.end(), 13) == surface.end());  // the centre

    SimulatedBody simulated;
    simulated.experiment = testing::tiny_experiment({3, 3, 3});
    simulated.replay = replay;
    engine::VoxelPoses poses;
    poses.time_s = 0.0;
    for (int v = 0; v < 27; ++v) {
        poses.position_m.insert(poses.position_m.end(),
                                {0.01f * (v % 3), 0.01f * (v / 3 % 3), 0.01f * (v / 9)});
        poses.orientation.insert(poses.orientation.end(), {1, 0, 0, 0});
        poses.size_m.insert(poses.size_m.end(), {0.01f, 0.01f, 0.01f});
    }
    simulated.replay.frames = {poses};
    simulated.surface_voxels = surface;
    ViewState view;
    const auto scene = simulation_scene(simulated, 0.0, view);
    CHECK(scene.body.voxel_count() == 26);
    CHECK(scene.body.poses.voxel_count() == 26);
    // Voxel 14 (cell (2, 1, 1)) is the 14th drawn (the centre, 13, is skipped): same position.
    CHECK(scene.body.voxel_cell[13] == 14);
    CHECK(scene.body.poses.position_m[3 * 13] == poses.position_m[3 * 14]);
    CHECK(render::build_draw_list(scene).voxel_instance_count() == 26);
}

TEST_CASE("studio scene: the face tints over the voxels on a face hold still as the camera turns") {
    // Issue 39, a low: in Workspace mode the workspace's face tints (the renderer's face quads and
    // the painter's second green layer over fixed faces) lay in the plane of the voxels on that
    // face and fought them in the depth buffer: a speckle that changed with every turn of the
    // camera (the faces flickered). A turn of a thousandth of a radian moves the picture by well
    // under a pixel, so only pixels on edges may change: at most 0.3 % of the window here, against
    // 2.5-5.6 % with the speckle.
    auto e = testing::tiny_experiment({6, 4, 4});
    // Voxels of a material on the outer layer of every face (the frame would be translucent).
    for (int x = 0; x < 6; ++x)
        for (int y = 0; y < 4; ++y)
            for (int z = 0; z < 4; ++z)
                if (x == 0 || y == 0 || z == 0 || x == 5 || y == 3 || z == 3)
                    e = with_override(e, {x, y, z}, PaintKind::Material, 1);
    e.boundary.faces[static_cast<int>(evo::Face::ZMax)] = evo::BoundaryKind::Fixed;
    Studio studio;
    studio.document.reset(e, "");
    HeadlessStudio session(studio, 900, 640);
    session.frame();  // frames the workspace
    double worst = 0.0;
    for (const float yaw : {-0.9425f, 0.6f, 2.2f, 3.8f}) {
        for (const float pitch : {0.534f, -0.45f}) {
            studio.view.camera.yaw_rad = yaw;
            studio.view.camera.pitch_rad = pitch;
            session.frame();
            const render::Image before = session.capture();
            studio.view.camera.yaw_rad = yaw + 1e-3f;
            session.frame();
            const auto moved = render::compare_images(before, session.capture(), 6);
            CAPTURE(yaw);
            CAPTURE(pitch);
            CHECK(moved.fraction_over < 0.006);
            worst = std::max(worst, moved.fraction_over);
        }
    }
    MESSAGE("largest fraction of pixels changed by a turn: " << worst);
}

TEST_CASE("studio scene: the bottom face's tint lies over the floor, not under it") {
    // The floor is at z = 0, pushed back in depth only a little: a tint moved below the
    // workspace's bottom face, as the other faces' tints are moved outside, was half hidden by it.
    auto e = testing::tiny_experiment({4, 3, 3});
    e.boundary.faces[static_cast<int>(evo::Face::ZMin)] = evo::BoundaryKind::Fixed;
    PainterState painter;
    const auto list = workspace_draw_list(e, painter, nullptr, true);
    const float voxel = static_cast<float>(e.voxel_size_m);
    int bottom = 0;
    for (const auto& v : list.translucent_triangles) {
        CHECK(v.position.z >= 0.0f);
        bottom += v.position.z > 0.0f && v.position.z < 0.1f * voxel;
    }
    CHECK(bottom == 12);  // the renderer's tint and the painter's green layer, just above z = 0
}
