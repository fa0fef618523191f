#include "app/gui/view/picking.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <utility>

#include <glm/geometric.hpp>
#include <glm/mat4x4.hpp>
#include <glm/matrix.hpp>
#include <glm/vec4.hpp>

#include "render/face_culling.hpp"

namespace bhm::app::gui {

namespace {

constexpr float kInfinity = std::numeric_limits<float>::infinity();

glm::vec3 unproject(const glm::mat4& inverse_view_projection, glm::vec2 ndc, float depth) {
    const glm::vec4 p = inverse_view_projection * glm::vec4(ndc, depth, 1.0f);
    return glm::vec3(p) / p.w;
}

// Slab test: the parameter interval where the ray is inside the box, and the axis/side of entry.
struct SlabResult {
    float t_enter = -kInfinity, t_exit = kInfinity;
    int enter_axis = -1;
    bool enter_max_side = false;
};

SlabResult slabs(const Ray& ray, glm::vec3 lo, glm::vec3 hi) {
    SlabResult r;
    for (int axis = 0; axis < 3; ++axis) {
        const float o = ray.origin[axis], d = ray.direction[axis];
        if (std::abs(d) < 1e-12f) {
            if (o < lo[axis] || o > hi[axis]) {
                r.t_exit = -kInfinity;  // parallel and outside: a miss
                return r;
            }
            continue;
        }
        float t0 = (lo[axis] - o) / d, t1 = (hi[axis] - o) / d;
        bool enter_max = false;
        if (t0 > t1) {
            std::swap(t0, t1);
            enter_max = true;  // moving toward -axis: enters through the max side
        }
        if (t0 > r.t_enter) {
            r.t_enter = t0;
            r.enter_axis = axis;
            r.enter_max_side = enter_max;
        }
        r.t_exit = std::min(r.t_exit, t1);
    }
    return r;
}

}  // namespace

Ray ray_through_pixel(const render::Camera& camera, glm::vec2 pixel, glm::vec2 viewport_px) {
    const float aspect = viewport_px.x / std::max(1.0f, viewport_px.y);
    const glm::mat4 inverse = glm::inverse(camera.view_projection(aspect));
    const glm::vec2 ndc{2.0f * pixel.x / viewport_px.x - 1.0f,
                        1.0f - 2.0f * pixel.y / viewport_px.y};
    const glm::vec3 near_point = unproject(inverse, ndc, -1.0f);
    const glm::vec3 far_point = unproject(inverse, ndc, 1.0f);
    return {near_point, glm::normalize(far_point - near_point)};
}

std::optional<glm::vec2> project_to_pixel(const render::Camera& camera, glm::vec3 point_m,
                                          glm::vec2 viewport_px) {
    const float aspect = viewport_px.x / std::max(1.0f, viewport_px.y);
    const glm::vec4 clip = camera.view_projection(aspect) * glm::vec4(point_m, 1.0f);
    if (clip.w <= 0.0f) return std::nullopt;
    const glm::vec2 ndc = glm::vec2(clip) / clip.w;
    return glm::vec2{(ndc.x + 1.0f) * 0.5f * viewport_px.x, (1.0f - ndc.y) * 0.5f * viewport_px.y};
}

glm::vec3 LatticeBox::max_corner() const {
    const float s = static_cast<float>(voxel_size_m);
    return {size[0] * s, size[1] * s, size[2] * s};
}

bool LatticeBox::contains_cell(const std::array<int, 3>& cell) const {
    for (int a = 0; a < 3; ++a)
        if (cell[a] < 0 || cell[a] >= size[a]) return false;
    return true;
}

std::optional<FaceHit> pick_box_face(const Ray& ray, const LatticeBox& box) {
    const SlabResult r = slabs(ray, glm::vec3(0.0f), box.max_corner());
    if (r.enter_axis < 0 || r.t_enter > r.t_exit || r.t_enter < 0.0f) return std::nullopt;
    FaceHit hit;
    hit.face = static_cast<evo::Face>(2 * r.enter_axis + (r.enter_max_side ? 1 : 0));
    hit.distance_m = r.t_enter;
    hit.point_m = ray.origin + r.t_enter * ray.direction;
    return hit;
}

glm::vec3 face_centre_m(const LatticeBox& box, evo::Face face) {
    glm::vec3 c = 0.5f * box.max_corner();
    const int axis = static_cast<int>(face) / 2;
    c[axis] = (static_cast<int>(face) % 2 == 1) ? box.max_corner()[axis] : 0.0f;
    return c;
}

void walk_cells(const Ray& ray, const LatticeBox& box,
                const std::function<bool(const std::array<int, 3>&)>& visit) {
    const glm::vec3 hi = box.max_corner();
    const SlabResult r = slabs(ray, glm::vec3(0.0f), hi);
    if (r.t_enter > r.t_exit || r.t_exit < 0.0f) return;
    const float s = static_cast<float>(box.voxel_size_m);
    const float t_start = std::max(r.t_enter, 0.0f);
    // Start a hair inside the box so the first cell is the one entered, not its neighbour.
    const glm::vec3 start = ray.origin + (t_start + 1e-5f * s) * ray.direction;
    std::array<int, 3> cell{}, step{};
    glm::vec3 t_max{kInfinity}, t_delta{kInfinity};
    for (int a = 0; a < 3; ++a) {
        cell[a] = std::clamp(static_cast<int>(std::floor(start[a] / s)), 0, box.size[a] - 1);
        const float d = ray.direction[a];
        if (d > 1e-12f) {
            step[a] = 1;
            t_max[a] = ((cell[a] + 1) * s - ray.origin[a]) / d;
            t_delta[a] = s / d;
        } else if (d < -1e-12f) {
            step[a] = -1;
            t_max[a] = (cell[a] * s - ray.origin[a]) / d;
            t_delta[a] = -s / d;
        }
    }
    while (box.contains_cell(cell)) {
        if (!visit(cell)) return;
        int axis = 0;
        if (t_max[1] < t_max[axis]) axis = 1;
        if (t_max[2] < t_max[axis]) axis = 2;
        if (t_max[axis] == kInfinity) return;
        cell[axis] += step[axis];
        t_max[axis] += t_delta[axis];
    }
}

std::optional<CellHit> pick_cell(const Ray& ray, const LatticeBox& box, const Slice& slice,
                                 const std::function<bool(const std::array<int, 3>&)>& occupied) {
    std::optional<CellHit> first_visible, first_in_top_layer, hit;
    walk_cells(ray, box, [&](const std::array<int, 3>& cell) {
        if (slice.hides(cell)) return true;
        if (!first_visible) first_visible = CellHit{cell, false};
        if (slice.axis >= 0 && !first_in_top_layer && cell[slice.axis] == slice.layer)
            first_in_top_layer = CellHit{cell, false};
        if (occupied && occupied(cell)) {
            hit = CellHit{cell, true};
            return false;
        }
        return true;
    });
    if (hit) return hit;
    if (first_in_top_layer) return first_in_top_layer;
    return first_visible;
}

std::optional<float> ray_box_distance(const Ray& ray, glm::vec3 centre, const float* q,
                                      glm::vec3 size) {
    // The ray in the box's own frame: rotated by the inverse of q (w, x, y, z) as the renderer
    // rotates the box by q (a degenerate q is the identity there too), then slabs.
    glm::vec4 inverse{q[0], -q[1], -q[2], -q[3]};
    const float norm = glm::length(inverse);
    inverse = norm > 1e-6f && std::isfinite(norm) ? inverse / norm : glm::vec4(1, 0, 0, 0);
    const glm::vec3 origin = render::rotate_vector(inverse, ray.origin - centre);
    const glm::vec3 direction = render::rotate_vector(inverse, ray.direction);
    const glm::vec3 half = 0.5f * size;
    float enter = -std::numeric_limits<float>::infinity();
    float leave = std::numeric_limits<float>::infinity();
    for (int a = 0; a < 3; ++a) {
        if (std::abs(direction[a]) < 1e-12f) {
            if (origin[a] < -half[a] || origin[a] > half[a]) return std::nullopt;
            continue;
        }
        float t0 = (-half[a] - origin[a]) / direction[a];
        float t1 = (half[a] - origin[a]) / direction[a];
        if (t0 > t1) std::swap(t0, t1);
        enter = std::max(enter, t0);
        leave = std::min(leave, t1);
    }
    if (enter > leave || leave < 0.0f) return std::nullopt;
    return std::max(0.0f, enter);
}

std::optional<VoxelHit> pick_posed_voxel(const Ray& ray, const engine::VoxelPoses& poses) {
    std::optional<VoxelHit> best;
    for (int v = 0; v < poses.voxel_count(); ++v) {
        const auto i = static_cast<std::size_t>(v);
        const glm::vec3 centre{poses.position_m[3 * i], poses.position_m[3 * i + 1],
                               poses.position_m[3 * i + 2]};
        const glm::vec3 size{poses.size_m[3 * i], poses.size_m[3 * i + 1],
                             poses.size_m[3 * i + 2]};
        const auto d = ray_box_distance(ray, centre, &poses.orientation[4 * i], size);
        if (d && (!best || *d < best->distance_m)) best = VoxelHit{v, *d};
    }
    return best;
}

}  // namespace bhm::app::gui
