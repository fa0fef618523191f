// The GL renderer on OSMesa (llvmpipe): golden images of the reference body, clear differences
// between states, extreme bodies without GL errors, clear errors for broken shaders.
#include <doctest/doctest.h>

#include <glad/gl.h>

#include <cstdlib>
#include <filesystem>
#include <fstream>

#include "render/gl_check.hpp"
#include "render/shader_program.hpp"
#include "tests/render/golden.hpp"
#include "tests/render/render_fixtures.hpp"

using namespace bhm::render;
using namespace bhm::render::testing;

namespace {

// Pixels whose colour is within tolerance of rgb (0..255) after lighting: counts hue matches.
int count_reddish(const Image& image) {
    int n = 0;
    for (int y = 0; y < image.height; ++y)
        for (int x = 0; x < image.width; ++x) {
            const auto* p = image.pixel(x, y);
            n += p[0] > 120 && p[0] > 2 * p[1] && p[0] > 2 * p[2];
        }
    return n;
}

Scene cube_scene(int n, std::uint8_t material) {
    bhm::engine::BodySpec spec;
    spec.nx = spec.ny = spec.nz = n;
    spec.material.assign(static_cast<std::size_t>(spec.cell_count()), material);
    Scene scene;
    scene.body = body_view_from_spec(spec);
    scene.material_colors = {palette::kActive, palette::kPassive, palette::kEnclosure};
    scene.faces[0] = FaceMarking::Fixed;
    scene.faces[1] = FaceMarking::Free;
    return scene;
}

}  // namespace

TEST_CASE("golden: mixed body, iso view") {
    check_golden("mixed_iso", render_scene(mixed_scene(), NamedView::Iso));
}

TEST_CASE("golden: mixed body, front section through y = 1") {
    Scene scene = mixed_scene();
    scene.options.section_y = 1;
    check_golden("mixed_front_section", render_scene(scene, NamedView::Front));
}

TEST_CASE("golden: curled body coloured by displacement, ghost of the rest state") {
    Scene scene = mixed_scene();
    scene.ghost_poses = scene.body.poses;
    scene.body.poses = curled_poses(scene.body);
    scene.options.show_ghost = true;
    scene.options.color_mode = ColorMode::Scalar;
    scene.options.voxel_scalar = voxel_displacement_m(scene.body.poses, *scene.ghost_poses);
    scene.options.scalar_range = {0.0f, 0.01f};
    check_golden("curled_displacement", render_scene(scene, NamedView::Iso));
}

TEST_CASE("a deformed state renders clearly differently from the rest state") {
    Scene scene = mixed_scene();
    const Image rest = render_scene(scene, NamedView::Iso);
    scene.body.poses = curled_poses(scene.body);
    const Image curled = render_scene(scene, NamedView::Iso);
    const ImageDifference d = compare_images(rest, curled, 16);
    CHECK(d.fraction_over > 0.05);  // far beyond the golden tolerance of 0.5 %
    CHECK(d.mean_abs_diff > 10.0 * kMaxMeanDiff);
    // Rendering is deterministic: the same scene twice gives the same pixels.
    const ImageDifference again = compare_images(curled, render_scene(scene, NamedView::Iso), 0);
    CHECK(again.max_diff == 0);
}

TEST_CASE("the front section hides what lies beyond the cut") {
    Scene scene = cube_scene(3, kPassive);
    scene.body.voxel_material[static_cast<std::size_t>(scene.body.voxel_count() - 1)] =
        kActive;  // (2,2,2)
    scene.options.show_origin_star = false;
    scene.options.show_axes = false;  // its x axis is red too
    // Seen from +y, the red voxel at y = 2 is in front; cut at y = 1 it is gone.
    CHECK(count_reddish(render_scene(scene, NamedView::Front)) > 500);
    scene.options.section_y = 1;
    CHECK(count_reddish(render_scene(scene, NamedView::Front)) == 0);
}

TEST_CASE("empty body, one voxel and a 40 x 40 x 40 block render without GL errors") {
    Scene empty;
    empty.body.nx = empty.body.ny = empty.body.nz = 8;
    CHECK_NOTHROW(render_scene(empty, NamedView::Iso));
    CHECK_NOTHROW(render_scene(empty, NamedView::Top));

    Scene one = cube_scene(1, kActive);
    one.options.show_origin_star = false;
    one.options.show_axes = false;
    const Image image = render_scene(one, NamedView::Iso);
    CHECK(count_reddish(image) > 2000);  // framed to fill much of 320 x 240
    // The centre of the image is the voxel.
    const auto* centre = image.pixel(160, 120);
    CHECK(centre[0] > 2 * centre[1]);

    Scene big = cube_scene(40, kPassive);
    Image large;
    CHECK_NOTHROW(large = render_scene(big, NamedView::Iso));
    CHECK_NOTHROW(render_scene(big, NamedView::Front));
    // 64,000 voxels of which only the 9,128 on the surface keep faces.
    const DrawList list = build_draw_list(big);
    int shown = 0;
    for (const auto& b : list.boxes)
        shown += b.faces > 0.5f;
    CHECK(shown == 64000 - 38 * 38 * 38);
}

TEST_CASE("any GL error fails the frame with the step that caused it") {
    shared_renderer();
    glEnable(0x1234);  // not a capability: GL_INVALID_ENUM
    CHECK_THROWS_WITH(check_gl_error("the test's bad call"),
                      doctest::Contains("GL_INVALID_ENUM after the test's bad call"));
    CHECK_NOTHROW(check_gl_error("nothing"));  // drained
}

TEST_CASE("a shader that does not compile names its file and the driver's log") {
    shared_target();
    const auto dir = std::filesystem::path(BHM_BINARY_DIR) / "test-render-tmp" / "bad-shaders";
    std::filesystem::create_directories(dir);
    for (const char* name : {"box.vert", "line.vert", "line.geom", "flat.vert", "flat.frag",
                             "marker.vert", "background.vert", "background.frag"})
        std::ofstream(dir / name) << shader_source(name);
    std::ofstream(dir / "box.frag")
        << "#version 330 core\nout vec4 c;\nvoid main() { c = undefined_thing; }\n";
    setenv("BHM_SHADER_DIR", dir.string().c_str(), 1);
    std::string message;
    try {
        Renderer renderer;
    } catch (const std::exception& e) {
        message = e.what();
    }
    unsetenv("BHM_SHADER_DIR");
    CHECK(message.find("shaders/box.frag: compile failed") != std::string::npos);
    CHECK(message.find("undefined_thing") != std::string::npos);
    CHECK_THROWS_WITH(shader_source("nope.frag"), doctest::Contains("nope.frag"));
}

TEST_CASE("the off-screen target reads back top row first at any size") {
    OffscreenTarget& target = shared_target(64, 48);
    // Clear the top half red, bottom half blue with scissors (GL's y runs upward).
    glEnable(GL_SCISSOR_TEST);
    glScissor(0, 24, 64, 24);
    glClearColor(1, 0, 0, 1);
    glClear(GL_COLOR_BUFFER_BIT);
    glScissor(0, 0, 64, 24);
    glClearColor(0, 0, 1, 1);
    glClear(GL_COLOR_BUFFER_BIT);
    glDisable(GL_SCISSOR_TEST);
    const Image image = target.read_image();
    CHECK(image.width == 64);
    CHECK(image.height == 48);
    CHECK(image.pixel(10, 2)[0] == 255);
    CHECK(image.pixel(10, 2)[2] == 0);
    CHECK(image.pixel(10, 45)[2] == 255);
    CHECK(image.pixel(10, 45)[0] == 0);
    CHECK_THROWS_WITH(OffscreenTarget(0, 10), doctest::Contains("outside 1..16384"));
}
