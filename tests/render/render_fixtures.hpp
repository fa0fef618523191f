#pragma once
// Bodies, scenes and a shared off-screen target for the renderer's tests.
#include <cmath>
#include <memory>
#include <string>

#include "render/draw_list.hpp"
#include "render/offscreen.hpp"
#include "render/renderer.hpp"
#include "render/replay_view.hpp"
#include "render/scene.hpp"

namespace bhm::render::testing {

inline constexpr std::uint8_t kActive = 1, kPassive = 2, kEnclosure = 3;

//! A 6 x 4 x 3 body: passive base, active top, a hole, the x = 0 layer held (fixed face x-).
inline engine::BodySpec mixed_body_spec() {
    engine::BodySpec spec;
    spec.nx = 6, spec.ny = 4, spec.nz = 3;
    spec.voxel_size_m = 0.01;
    spec.material.assign(static_cast<std::size_t>(spec.cell_count()), 0);
    spec.fixed.assign(static_cast<std::size_t>(spec.cell_count()), 0);
    for (int z = 0; z < spec.nz; ++z)
        for (int y = 0; y < spec.ny; ++y)
            for (int x = 0; x < spec.nx; ++x) {
                const int c = spec.cell_index(x, y, z);
                if (z == 2 && y == 3 && x >= 3) continue;  // a notch on the top far corner
                if (x == 4 && y == 1 && z == 1) continue;  // a hole inside
                spec.material[static_cast<std::size_t>(c)] =
                    (z == 2 || (x + y) % 3 == 0) ? kActive : kPassive;
                spec.fixed[static_cast<std::size_t>(c)] = x == 0;
            }
    return spec;
}

inline Scene mixed_scene() {
    Scene scene;
    scene.body = body_view_from_spec(mixed_body_spec());
    scene.workspace = {8, 5, 4};
    scene.material_colors = {palette::kActive, palette::kPassive, palette::kEnclosure};
    scene.faces[0] = FaceMarking::Fixed;
    scene.faces[1] = FaceMarking::Free;
    return scene;
}

//! The body curled upward about y: voxel at lattice x turned by 0.12 rad per voxel length and
//! moved along the arc; active voxels 15 % longer along x. A clear, known deformation.
inline engine::VoxelPoses curled_poses(const BodyView& body) {
    engine::VoxelPoses poses = rest_poses(body);
    const float s = static_cast<float>(body.voxel_size_m);
    const float radius = s / 0.12f;  // bend radius: 0.12 rad per voxel
    for (int v = 0; v < body.voxel_count(); ++v) {
        const auto c = body.voxel_coords(v);
        const std::size_t i = static_cast<std::size_t>(v);
        const float arc = (static_cast<float>(c[0]) + 0.5f) * s;
        const float angle = arc / radius;
        const float r = radius - (static_cast<float>(c[2]) + 0.5f) * s;
        poses.position_m[3 * i] = r * std::sin(angle);
        poses.position_m[3 * i + 2] = radius - r * std::cos(angle);
        // Rotation by -angle about y (the curl lifts the +x end): q = (cos(a/2), 0, -sin(a/2), 0).
        poses.orientation[4 * i] = std::cos(0.5f * angle);
        poses.orientation[4 * i + 2] = -std::sin(0.5f * angle);
        if (body.voxel_material[i] == kActive) poses.size_m[3 * i] = 1.15f * s;
    }
    return poses;
}

//! One off-screen target and renderer for all GL tests of this binary (creating llvmpipe
//! contexts is slow). Never destroyed: Mesa's own exit handlers run before static destructors
//! and a context torn down after them crashes (seen with DISPLAY set).
struct SharedGl {
    std::unique_ptr<OffscreenTarget> target;
    std::unique_ptr<Renderer> renderer;
};

inline SharedGl& shared_gl() {
    static SharedGl* gl = new SharedGl;  // reachable until exit, so not a leak
    return *gl;
}

inline OffscreenTarget& shared_target(int width = 320, int height = 240) {
    auto& target = shared_gl().target;
    if (!target) target = std::make_unique<OffscreenTarget>(width, height, 4);
    if (target->width() != width || target->height() != height) target->resize(width, height);
    target->bind();
    return *target;
}

inline Renderer& shared_renderer() {
    shared_target();
    auto& renderer = shared_gl().renderer;
    if (!renderer) renderer = std::make_unique<Renderer>();
    return *renderer;
}

//! Draws the scene from a named view framed to its bounds and reads the image back.
inline Image render_scene(const Scene& scene, NamedView view, int width = 320, int height = 240) {
    Renderer& renderer = shared_renderer();
    OffscreenTarget& target = shared_target(width, height);
    const DrawList list = build_draw_list(scene);
    const Camera camera =
        named_view(view, list.bounds, static_cast<float>(width) / static_cast<float>(height));
    renderer.draw(list, camera, width, height);
    return target.read_image();
}

}  // namespace bhm::render::testing
