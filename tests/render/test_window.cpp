// The on-screen path: a GLFW window draws the same scene. Needs a display: run the suite under
// xvfb-run -a -s '-screen 0 1280x800x24' to include it; without DISPLAY it is skipped.
// The window lives in a child process, away from the other tests' shared OSMesa context: glad's
// pointers are process-wide, and this test should not depend on the order tests run in.
#include <doctest/doctest.h>

#include <glad/gl.h>

#include <sys/wait.h>
#include <unistd.h>

#include <cstdio>
#include <cstdlib>
#include <exception>
#include <vector>

#include "render/window.hpp"
#include "tests/render/render_fixtures.hpp"

using namespace bhm::render;
using namespace bhm::render::testing;

namespace {

// 0: drawn, the centre is not background; 1: the picture is wrong; 2: an exception.
int draw_in_window() {
    try {
        Window window(320, 240, "bhm render test", 1);
        window.bind();
        Renderer renderer;
        const DrawList list = build_draw_list(mixed_scene());
        const Camera camera = named_view(NamedView::Iso, list.bounds, 320.0f / 240.0f);
        renderer.draw(list, camera, window.framebuffer_width(), window.framebuffer_height());
        std::vector<unsigned char> pixel(4);
        glReadPixels(window.framebuffer_width() / 2, window.framebuffer_height() / 2, 1, 1, GL_RGBA,
                     GL_UNSIGNED_BYTE, pixel.data());
        window.swap_buffers();
        if (pixel[0] + pixel[1] + pixel[2] >= 3 * 220) {
            std::fprintf(stderr, "window centre is background: %d %d %d\n", pixel[0], pixel[1],
                         pixel[2]);
            return 1;
        }
        return 0;
    } catch (const std::exception& e) {
        std::fprintf(stderr, "window: %s\n", e.what());
        return 2;
    }
}

}  // namespace

TEST_CASE("a GLFW window draws the scene without GL errors") {
    const char* display = std::getenv("DISPLAY");
    if (!display || !*display) {
        MESSAGE("skipped: no DISPLAY (run under xvfb-run to include the window path)");
        return;
    }
    std::fflush(nullptr);
    const pid_t child = fork();
    REQUIRE(child >= 0);
    if (child == 0) _exit(draw_in_window());
    int status = 0;
    REQUIRE(waitpid(child, &status, 0) == child);
    REQUIRE(WIFEXITED(status));
    CHECK(WEXITSTATUS(status) == 0);  // 1: wrong picture, 2: an exception (printed above)
}
