// The on-screen path: a GLFW window draws the same scene. Needs a display: run the suite under
// xvfb-run -a -s '-screen 0 1280x800x24' to include it; without DISPLAY it is skipped.
#include <doctest/doctest.h>

#include <glad/gl.h>

#include <cstdlib>
#include <vector>

#include "render/window.hpp"
#include "tests/render/render_fixtures.hpp"

using namespace bhm::render;
using namespace bhm::render::testing;

TEST_CASE("a GLFW window draws the scene without GL errors") {
    const char* display = std::getenv("DISPLAY");
    if (!display || !*display) {
        MESSAGE("skipped: no DISPLAY (run under xvfb-run to include the window path)");
        return;
    }
    Window window(320, 240, "bhm render test", 1);
    window.bind();
    {
        Renderer renderer;
        const DrawList list = build_draw_list(mixed_scene());
        const Camera camera = named_view(NamedView::Iso, list.bounds, 320.0f / 240.0f);
        CHECK_NOTHROW(
            renderer.draw(list, camera, window.framebuffer_width(), window.framebuffer_height()));
        // The back buffer holds the picture: its centre is not the background.
        std::vector<unsigned char> pixel(4);
        glReadPixels(window.framebuffer_width() / 2, window.framebuffer_height() / 2, 1, 1, GL_RGBA,
                     GL_UNSIGNED_BYTE, pixel.data());
        CHECK(pixel[0] + pixel[1] + pixel[2] < 3 * 220);
        window.swap_buffers();
    }
}
