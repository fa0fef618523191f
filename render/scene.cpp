#include "render/scene.hpp"

namespace bhm::render {

std::array<int, 3> BodyView::voxel_coords(int v) const {
    const int cell = voxel_cell[static_cast<std::size_t>(v)];
    return {cell % nx, (cell / nx) % ny, cell / (nx * ny)};
}

glm::vec3 cell_centre_m(int x, int y, int z, double voxel_size_m) {
    const double s = voxel_size_m;
    return {static_cast<float>((x + 0.5) * s), static_cast<float>((y + 0.5) * s),
            static_cast<float>((z + 0.5) * s)};
}

BodyView body_view_from_spec(const engine::BodySpec& spec) {
    BodyView body;
    body.nx = spec.nx, body.ny = spec.ny, body.nz = spec.nz;
    body.voxel_size_m = spec.voxel_size_m;
    for (int cell = 0; cell < spec.cell_count(); ++cell) {
        const auto material = spec.material[static_cast<std::size_t>(cell)];
        if (material == 0) continue;
        body.voxel_cell.push_back(cell);
        body.voxel_material.push_back(material);
        const bool held = !spec.fixed.empty() && spec.fixed[static_cast<std::size_t>(cell)] != 0;
        body.voxel_fixed.push_back(held ? 1 : 0);
    }
    body.poses = rest_poses(body);
    return body;
}

engine::VoxelPoses rest_poses(const BodyView& body) {
    engine::VoxelPoses poses;
    const int n = body.voxel_count();
    poses.position_m.reserve(3 * static_cast<std::size_t>(n));
    poses.orientation.reserve(4 * static_cast<std::size_t>(n));
    poses.size_m.reserve(3 * static_cast<std::size_t>(n));
    const float s = static_cast<float>(body.voxel_size_m);
    for (int v = 0; v < n; ++v) {
        const auto [x, y, z] = body.voxel_coords(v);
        const glm::vec3 c = cell_centre_m(x, y, z, body.voxel_size_m);
        poses.position_m.insert(poses.position_m.end(), {c.x, c.y, c.z});
        poses.orientation.insert(poses.orientation.end(), {1.0f, 0.0f, 0.0f, 0.0f});
        poses.size_m.insert(poses.size_m.end(), {s, s, s});
    }
    return poses;
}

}  // namespace bhm::render
