#include "render/camera.hpp"

#include <algorithm>
#include <cmath>

#include <glm/glm.hpp>

#include <glm/gtc/matrix_transform.hpp>

namespace bhm::render {

namespace {
constexpr float kPi = 3.14159265358979f;
// Keeps the basis well defined: the eye never sits exactly on the z axis while orbiting.
constexpr float kMaxOrbitPitch = 0.5f * kPi - 0.01f;
}  // namespace

void Bounds::add(const glm::vec3& point) {
    if (!valid) {
        min = max = point;
        valid = true;
        return;
    }
    min = glm::min(min, point);
    max = glm::max(max, point);
}

void Bounds::add(const Bounds& other) {
    if (!other.valid) return;
    add(other.min);
    add(other.max);
}

float Bounds::radius() const {
    return valid ? 0.5f * glm::length(max - min) : 0.0f;
}

std::optional<NamedView> parse_named_view(const std::string& name) {
    if (name == "iso") return NamedView::Iso;
    if (name == "front") return NamedView::Front;
    if (name == "top") return NamedView::Top;
    if (name == "side") return NamedView::Side;
    return std::nullopt;
}

const char* named_view_name(NamedView view) {
    switch (view) {
        case NamedView::Front:
            return "front";
        case NamedView::Top:
            return "top";
        case NamedView::Side:
            return "side";
        case NamedView::Iso:
        default:
            return "iso";
    }
}

glm::vec3 Camera::eye_direction() const {
    const float cp = std::cos(pitch_rad);
    return {cp * std::cos(yaw_rad), cp * std::sin(yaw_rad), std::sin(pitch_rad)};
}

// The right vector depends on yaw only, so the basis stays defined straight above (top view).
glm::vec3 Camera::right() const {
    return {-std::sin(yaw_rad), std::cos(yaw_rad), 0.0f};
}

glm::vec3 Camera::up() const {
    return glm::cross(right(), forward());
}

glm::vec3 Camera::eye_position() const {
    // Orthographic: the eye stands back beyond the scene so nothing framed is clipped; the
    // image scale comes from distance_m alone.
    const float d = orthographic ? distance_m + 2.0f * scene_radius_m : distance_m;
    return target + d * eye_direction();
}

float Camera::half_height_m() const {
    return distance_m * std::tan(0.5f * fov_y_rad);
}

glm::mat4 Camera::view_matrix() const {
    const glm::vec3 r = right(), u = up(), f = forward(), e = eye_position();
    glm::mat4 m(1.0f);
    m[0][0] = r.x, m[1][0] = r.y, m[2][0] = r.z;
    m[0][1] = u.x, m[1][1] = u.y, m[2][1] = u.z;
    m[0][2] = -f.x, m[1][2] = -f.y, m[2][2] = -f.z;
    m[3][0] = -glm::dot(r, e);
    m[3][1] = -glm::dot(u, e);
    m[3][2] = glm::dot(f, e);
    return m;
}

glm::mat4 Camera::projection_matrix(float aspect) const {
    const float radius = std::max(scene_radius_m, 1e-6f);
    if (orthographic) {
        const float h = half_height_m();
        const float eye_distance = distance_m + 2.0f * radius;
        return glm::ortho(-h * aspect, h * aspect, -h, h,
                          std::max(eye_distance - 4.0f * radius, 1e-4f * radius),
                          eye_distance + 4.0f * radius);
    }
    // Near plane just in front of the framed scene but never at the eye (depth precision).
    const float near_plane = std::max(distance_m - 2.0f * radius, 0.01f * distance_m);
    const float far_plane = distance_m + 4.0f * radius;
    return glm::perspective(fov_y_rad, aspect, near_plane, far_plane);
}

void orbit(Camera& camera, float dx_px, float dy_px, float radians_per_px) {
    camera.yaw_rad -= dx_px * radians_per_px;
    camera.yaw_rad = std::remainder(camera.yaw_rad, 2.0f * kPi);
    camera.pitch_rad =
        std::clamp(camera.pitch_rad + dy_px * radians_per_px, -kMaxOrbitPitch, kMaxOrbitPitch);
}

void pan(Camera& camera, float dx_px, float dy_px, int viewport_height_px) {
    const float metres_per_px =
        2.0f * camera.half_height_m() / static_cast<float>(std::max(viewport_height_px, 1));
    camera.target += (-dx_px * camera.right() + dy_px * camera.up()) * metres_per_px;
}

void zoom(Camera& camera, float factor) {
    if (!(factor > 0.0f)) return;
    camera.distance_m = std::clamp(camera.distance_m / factor, 1e-5f, 1e5f);
}

void frame_bounds(Camera& camera, const Bounds& bounds, float aspect, float margin) {
    if (!bounds.valid) return;
    camera.target = bounds.centre();
    camera.scene_radius_m = std::max(bounds.radius(), 1e-4f);
    const glm::vec3 r = camera.right(), u = camera.up(), f = camera.forward();
    const float fill = std::max(1.0f - 2.0f * margin, 0.1f);
    const float tan_y = std::tan(0.5f * camera.fov_y_rad) * fill;
    const float tan_x = tan_y * aspect;
    float needed = 1e-4f;
    for (int corner = 0; corner < 8; ++corner) {
        const glm::vec3 p{(corner & 1) ? bounds.max.x : bounds.min.x,
                          (corner & 2) ? bounds.max.y : bounds.min.y,
                          (corner & 4) ? bounds.max.z : bounds.min.z};
        const glm::vec3 d = p - camera.target;
        const float x = std::fabs(glm::dot(d, r)), y = std::fabs(glm::dot(d, u));
        if (camera.orthographic) {
            // The scale is the half height at any depth: fit both extents.
            needed = std::max({needed, y / tan_y, x / tan_x});
        } else {
            // A corner nearer the eye (depth along forward < 0) needs more distance to fit.
            const float depth = glm::dot(d, f);
            needed = std::max({needed, -depth + y / tan_y, -depth + x / tan_x});
        }
    }
    camera.distance_m = needed;
}

Camera named_view(NamedView view, const Bounds& bounds, float aspect) {
    Camera camera;
    camera.fov_y_rad = 0.55f;
    switch (view) {
        case NamedView::Iso:
            camera.yaw_rad = -0.30f * kPi;  // eye at +x, -y: x toward the viewer's right
            camera.pitch_rad = 0.17f * kPi;
            break;
        case NamedView::Front:
            camera.yaw_rad = 0.5f * kPi;  // eye at +y looking -y onto the section cut
            camera.orthographic = true;
            break;
        case NamedView::Top:
            camera.yaw_rad = -0.5f * kPi;  // right = +x, up = +y
            camera.pitch_rad = 0.5f * kPi;
            camera.orthographic = true;
            break;
        case NamedView::Side:
            camera.yaw_rad = 0.0f;  // eye at +x: y to the right, z up
            camera.orthographic = true;
            break;
    }
    frame_bounds(camera, bounds, aspect);
    return camera;
}

}  // namespace bhm::render
