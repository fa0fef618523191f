// The orbit camera: named views look the right way, framing fits, mouse moves do what they say.
#include <doctest/doctest.h>

#include <algorithm>
#include <cmath>

#include <glm/glm.hpp>
#include <glm/gtc/matrix_transform.hpp>

#include "render/camera.hpp"

using namespace bhm::render;

namespace {

Bounds box(glm::vec3 lo, glm::vec3 hi) {
    Bounds b;
    b.add(lo);
    b.add(hi);
    return b;
}

glm::vec3 to_ndc(const Camera& camera, float aspect, glm::vec3 p) {
    const glm::vec4 clip = camera.view_projection(aspect) * glm::vec4(p, 1.0f);
    return glm::vec3(clip) / clip.w;
}

void check_vec(glm::vec3 a, glm::vec3 b) {
    CHECK(a.x == doctest::Approx(b.x).epsilon(1e-5));
    CHECK(a.y == doctest::Approx(b.y).epsilon(1e-5));
    CHECK(a.z == doctest::Approx(b.z).epsilon(1e-5));
}

const Bounds kWorkspace = box({0, 0, 0}, {0.08f, 0.08f, 0.07f});  // the paper's 8 x 8 x 7

}  // namespace

TEST_CASE("named views look along the documented axes") {
    const Camera front = named_view(NamedView::Front, kWorkspace, 1.5f);
    check_vec(front.forward(), {0, -1, 0});
    check_vec(front.up(), {0, 0, 1});
    CHECK(front.orthographic);
    const Camera top = named_view(NamedView::Top, kWorkspace, 1.5f);
    check_vec(top.forward(), {0, 0, -1});
    check_vec(top.right(), {1, 0, 0});
    check_vec(top.up(), {0, 1, 0});
    const Camera side = named_view(NamedView::Side, kWorkspace, 1.5f);
    check_vec(side.forward(), {-1, 0, 0});
    check_vec(side.right(), {0, 1, 0});
    const Camera iso = named_view(NamedView::Iso, kWorkspace, 1.5f);
    CHECK_FALSE(iso.orthographic);
    // From above, in front (-y) and to the +x side.
    CHECK(iso.eye_direction().x > 0.3f);
    CHECK(iso.eye_direction().y < -0.3f);
    CHECK(iso.eye_direction().z > 0.3f);
    for (const char* name : {"iso", "front", "top", "side"})
        CHECK(named_view_name(*parse_named_view(name)) == std::string(name));
    CHECK_FALSE(parse_named_view("diagonal"));
}

TEST_CASE("the view matrix agrees with glm::lookAt from the eye") {
    Camera camera;
    camera.target = {0.1f, -0.2f, 0.3f};
    camera.yaw_rad = 0.7f;
    camera.pitch_rad = 0.4f;
    camera.distance_m = 2.0f;
    const glm::mat4 expected =
        glm::lookAt(camera.eye_position(), camera.target, glm::vec3(0, 0, 1));
    const glm::mat4 actual = camera.view_matrix();
    for (int c = 0; c < 4; ++c)
        for (int r = 0; r < 4; ++r)
            CHECK(actual[c][r] == doctest::Approx(expected[c][r]).epsilon(1e-5));
}

TEST_CASE("framing puts every corner of the bounds inside the viewport, with a margin") {
    for (NamedView view : {NamedView::Iso, NamedView::Front, NamedView::Top, NamedView::Side}) {
        for (float aspect : {0.5f, 1.0f, 16.0f / 9.0f}) {
            const Camera camera = named_view(view, kWorkspace, aspect);
            float extent = 0.0f;
            for (int corner = 0; corner < 8; ++corner) {
                const glm::vec3 p{(corner & 1) ? 0.08f : 0.0f, (corner & 2) ? 0.08f : 0.0f,
                                  (corner & 4) ? 0.07f : 0.0f};
                const glm::vec3 ndc = to_ndc(camera, aspect, p);
                CHECK(std::fabs(ndc.x) <= 0.89f);  // margin 6 % each side
                CHECK(std::fabs(ndc.y) <= 0.89f);
                CHECK(ndc.z > -1.0f);  // not clipped by the near or far plane
                CHECK(ndc.z < 1.0f);
                extent = std::max({extent, std::fabs(ndc.x), std::fabs(ndc.y)});
            }
            // Tight: the widest corner reaches the margin.
            CHECK(extent == doctest::Approx(0.88f).epsilon(0.01));
        }
    }
}

TEST_CASE("zoom scales the image about the target") {
    Camera camera = named_view(NamedView::Iso, kWorkspace, 1.0f);
    const glm::vec3 p{0.08f, 0.0f, 0.07f};
    const float d = camera.distance_m;
    zoom(camera, 2.0f);
    CHECK(camera.distance_m == doctest::Approx(d / 2));
    Camera ortho = named_view(NamedView::Front, kWorkspace, 1.0f);
    const glm::vec3 ortho_before = to_ndc(ortho, 1.0f, p) - to_ndc(ortho, 1.0f, ortho.target);
    zoom(ortho, 2.0f);
    const glm::vec3 ortho_after = to_ndc(ortho, 1.0f, p) - to_ndc(ortho, 1.0f, ortho.target);
    CHECK(ortho_after.x == doctest::Approx(2.0f * ortho_before.x));
    CHECK(ortho_after.y == doctest::Approx(2.0f * ortho_before.y));
    zoom(camera, 0.0f);  // ignored
    CHECK(camera.distance_m == doctest::Approx(d / 2));
}

TEST_CASE("pan moves the scene with the cursor, pixel for pixel, at the target's depth") {
    for (NamedView view : {NamedView::Iso, NamedView::Front}) {
        Camera camera = named_view(view, kWorkspace, 4.0f / 3.0f);
        const int w = 800, h = 600;
        const glm::vec3 p = camera.target;
        const glm::vec3 a = to_ndc(camera, 4.0f / 3.0f, p);
        // Drag right 40 px and up 30 px in window coordinates (y down); NDC has y up.
        pan(camera, 40.0f, -30.0f, h);
        const glm::vec3 b = to_ndc(camera, 4.0f / 3.0f, p);
        CHECK((b.x - a.x) * 0.5f * w == doctest::Approx(40.0f).epsilon(1e-3));
        CHECK((b.y - a.y) * 0.5f * h == doctest::Approx(30.0f).epsilon(1e-3));
    }
}

TEST_CASE("orbit turns with the drag and stops short of the poles") {
    Camera camera;
    orbit(camera, 100.0f, 0.0f, 0.01f);
    CHECK(camera.yaw_rad == doctest::Approx(-1.0f));
    orbit(camera, 0.0f, 1000.0f, 0.01f);
    CHECK(camera.pitch_rad < 1.5708f);
    CHECK(camera.pitch_rad > 1.5f);
    CHECK(glm::length(camera.up()) == doctest::Approx(1.0f));  // basis still defined
    orbit(camera, 0.0f, -5000.0f, 0.01f);
    CHECK(camera.pitch_rad > -1.5708f);
}

TEST_CASE("bounds grow with points and report centre and radius") {
    Bounds b;
    CHECK_FALSE(b.valid);
    b.add(glm::vec3(1, 2, 3));
    b.add(glm::vec3(-1, 0, 3));
    CHECK(b.valid);
    check_vec(b.centre(), {0, 1, 3});
    CHECK(b.radius() == doctest::Approx(std::sqrt(2.0f)));
    Bounds other;
    b.add(other);  // invalid: no change
    check_vec(b.max, {1, 2, 3});
}
