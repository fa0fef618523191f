#include "render/draw_list.hpp"

#include <cmath>
#include <stdexcept>
#include <string>

#include <glm/glm.hpp>

#include "render/face_culling.hpp"

namespace bhm::render {

namespace {

constexpr float kWorkspaceLinePx = 1.5f;
constexpr float kFaceOutlinePx = 2.0f;
constexpr float kGridLinePx = 1.0f;
constexpr float kTrailLinePx = 2.5f;

void add_line(std::vector<LineVertex>& lines, glm::vec3 a, glm::vec3 b, glm::vec4 color,
              float width_px) {
    lines.push_back({a, color, width_px});
    lines.push_back({b, color, width_px});
}

void add_quad(std::vector<TriangleVertex>& out, const glm::vec3 (&corner)[4], glm::vec4 color) {
    for (int i : {0, 1, 2, 0, 2, 3})
        out.push_back({corner[i], color});
}

glm::vec4 unit_quaternion(const float* wxyz) {
    const glm::vec4 q{wxyz[0], wxyz[1], wxyz[2], wxyz[3]};
    const float norm = glm::length(q);
    if (!(norm > 1e-6f) || !std::isfinite(norm)) return {1.0f, 0.0f, 0.0f, 0.0f};
    return q / norm;
}

// Half extent of a rotated box along the world axes (tight axis-aligned box): sum over the box's
// own axes of |rotated axis| x half size.
glm::vec3 rotated_half_extent(const BoxInstance& box) {
    const glm::vec3 half = 0.5f * box.size;
    glm::vec3 extent(0.0f);
    for (int axis = 0; axis < 3; ++axis) {
        glm::vec3 local(0.0f);
        local[axis] = half[axis];
        extent += glm::abs(rotate_vector(box.orientation, local));
    }
    return extent;
}

void check_pose_count(const engine::VoxelPoses& poses, int voxel_count, const char* what) {
    const std::size_t n = static_cast<std::size_t>(voxel_count);
    if (poses.position_m.size() != 3 * n || poses.orientation.size() != 4 * n ||
        poses.size_m.size() != 3 * n) {
        throw std::invalid_argument(std::string("render: ") + what + " hold " +
                                    std::to_string(poses.voxel_count()) + " voxels, the body has " +
                                    std::to_string(voxel_count));
    }
}

BoxInstance box_from_pose(const engine::VoxelPoses& poses, int v) {
    const std::size_t i = static_cast<std::size_t>(v);
    BoxInstance box;
    box.centre = {poses.position_m[3 * i], poses.position_m[3 * i + 1],
                  poses.position_m[3 * i + 2]};
    box.orientation = unit_quaternion(&poses.orientation[4 * i]);
    box.size = {poses.size_m[3 * i], poses.size_m[3 * i + 1], poses.size_m[3 * i + 2]};
    return box;
}

glm::vec4 material_color(const Scene& scene, int material) {
    if (material < 1 || material > static_cast<int>(scene.material_colors.size()))
        return palette::kUnknownMaterial;
    return scene.material_colors[static_cast<std::size_t>(material - 1)];
}

void check_body(const BodyView& body) {
    const int n = body.voxel_count();
    if (body.nx < 0 || body.ny < 0 || body.nz < 0)
        throw std::invalid_argument("render: negative lattice size");
    if (static_cast<int>(body.voxel_material.size()) != n)
        throw std::invalid_argument("render: voxel_material has " +
                                    std::to_string(body.voxel_material.size()) +
                                    " entries, the body has " + std::to_string(n) + " voxels");
    if (!body.voxel_fixed.empty() && static_cast<int>(body.voxel_fixed.size()) != n)
        throw std::invalid_argument("render: voxel_fixed has " +
                                    std::to_string(body.voxel_fixed.size()) +
                                    " entries, the body has " + std::to_string(n) + " voxels");
    const long long cells = static_cast<long long>(body.nx) * body.ny * body.nz;
    for (int v = 0; v < n; ++v) {
        const auto cell = body.voxel_cell[static_cast<std::size_t>(v)];
        if (cell < 0 || cell >= cells)
            throw std::invalid_argument("render: voxel " + std::to_string(v) + " lies in cell " +
                                        std::to_string(cell) + ", outside the " +
                                        std::to_string(body.nx) + "x" + std::to_string(body.ny) +
                                        "x" + std::to_string(body.nz) + " lattice");
    }
}

void add_body(const Scene& scene, DrawList& list) {
    const BodyView& body = scene.body;
    const SceneOptions& options = scene.options;
    const int n = body.voxel_count();
    const engine::VoxelPoses rest =
        body.poses.position_m.empty() ? rest_poses(body) : engine::VoxelPoses{};
    const engine::VoxelPoses& poses = body.poses.position_m.empty() ? rest : body.poses;
    check_pose_count(poses, n, "poses");
    const bool by_scalar = options.color_mode == ColorMode::Scalar;
    if (by_scalar && static_cast<int>(options.voxel_scalar.size()) != n)
        throw std::invalid_argument("render: voxel_scalar has " +
                                    std::to_string(options.voxel_scalar.size()) +
                                    " values, the body has " + std::to_string(n) + " voxels");
    if (by_scalar && !options.voxel_without_scalar.empty() &&
        static_cast<int>(options.voxel_without_scalar.size()) != n)
        throw std::invalid_argument("render: voxel_without_scalar has " +
                                    std::to_string(options.voxel_without_scalar.size()) +
                                    " flags, the body has " + std::to_string(n) + " voxels");
    std::vector<BoxInstance> placed;
    placed.reserve(static_cast<std::size_t>(n));
    for (int v = 0; v < n; ++v) {
        if (options.section_y >= 0 && body.voxel_coords(v)[1] > options.section_y) continue;
        BoxInstance box = box_from_pose(poses, v);
        const glm::vec4 base =
            material_color(scene, body.voxel_material[static_cast<std::size_t>(v)]);
        box.color = base;
        const bool has_scalar = options.voxel_without_scalar.empty() ||
                                !options.voxel_without_scalar[static_cast<std::size_t>(v)];
        if (by_scalar && has_scalar) {
            box.color = sample_color_map(
                options.color_map,
                options.scalar_range.normalize(options.voxel_scalar[static_cast<std::size_t>(v)]));
            box.color.a = base.a;
        }
        std::uint32_t flags = 0;
        if (!body.voxel_fixed.empty() && body.voxel_fixed[static_cast<std::size_t>(v)])
            flags |= kBoxFixed;
        if (!options.show_edges) flags |= kBoxNoEdges;
        box.flags = static_cast<float>(flags);
        box.voxel = static_cast<float>(v);
        list.bounds.add(box.centre - rotated_half_extent(box));
        list.bounds.add(box.centre + rotated_half_extent(box));
        placed.push_back(box);
    }
    cull_hidden_faces(body, placed);
    for (const auto& box : placed)
        (box.color.a < 0.999f ? list.translucent_boxes : list.boxes).push_back(box);
}

void add_ghost(const Scene& scene, DrawList& list) {
    const BodyView& body = scene.body;
    const auto& ghost = *scene.ghost_poses;
    check_pose_count(ghost, body.voxel_count(), "ghost poses");
    std::vector<BoxInstance> placed;
    for (int v = 0; v < body.voxel_count(); ++v) {
        if (scene.options.section_y >= 0 && body.voxel_coords(v)[1] > scene.options.section_y)
            continue;
        BoxInstance box = box_from_pose(ghost, v);
        box.centre += scene.options.ghost_offset_m;
        box.color = palette::kGhost;
        box.flags = static_cast<float>(kBoxGhost | (scene.options.show_edges ? 0u : kBoxNoEdges));
        box.voxel = static_cast<float>(v);
        list.bounds.add(box.centre - rotated_half_extent(box));
        list.bounds.add(box.centre + rotated_half_extent(box));
        placed.push_back(box);
    }
    cull_hidden_faces(body, placed);
    list.translucent_boxes.insert(list.translucent_boxes.end(), placed.begin(), placed.end());
}

void add_workspace_box(const Bounds& w, DrawList& list) {
    for (int axis = 0; axis < 3; ++axis) {
        const int a = (axis + 1) % 3, b = (axis + 2) % 3;
        for (int corner = 0; corner < 4; ++corner) {
            glm::vec3 p0 = w.min, p1 = w.max;
            p0[a] = p1[a] = (corner & 1) ? w.max[a] : w.min[a];
            p0[b] = p1[b] = (corner & 2) ? w.max[b] : w.min[b];
            p0[axis] = w.min[axis];
            p1[axis] = w.max[axis];
            add_line(list.lines, p0, p1, palette::kWorkspaceBox, kWorkspaceLinePx);
        }
    }
}

// The floor spans the workspace and the body wherever it went, plus a margin, on the voxel grid.
void add_floor(const Scene& scene, const Bounds& workspace, DrawList& list) {
    const float s = static_cast<float>(scene.body.voxel_size_m);
    Bounds area = workspace;
    area.add(list.bounds);
    const float margin = 2.0f * s;
    const float x0 = std::floor((area.min.x - margin) / s) * s,
                x1 = std::ceil((area.max.x + margin) / s) * s;
    const float y0 = std::floor((area.min.y - margin) / s) * s,
                y1 = std::ceil((area.max.y + margin) / s) * s;
    // A replay can hold any numbers (a diverged run, a damaged file): no floor at all when they
    // are not finite, no grid when it would need more lines than anyone could see.
    if (!std::isfinite(x0) || !std::isfinite(x1) || !std::isfinite(y0) || !std::isfinite(y1))
        return;
    const glm::vec3 corners[4] = {{x0, y0, 0}, {x1, y0, 0}, {x1, y1, 0}, {x0, y1, 0}};
    add_quad(list.floor, corners, palette::kFloor);
    constexpr float kMaxGridLines = 4096.0f;
    const float cells_x = (x1 - x0) / s, cells_y = (y1 - y0) / s;
    if (!(cells_x <= kMaxGridLines) || !(cells_y <= kMaxGridLines)) return;
    const int lines_x = static_cast<int>(std::lround(cells_x));
    const int lines_y = static_cast<int>(std::lround(cells_y));
    for (int i = 0; i <= lines_x; ++i) {
        const float x = x0 + static_cast<float>(i) * s;
        add_line(list.floor_lines, {x, y0, 0}, {x, y1, 0}, palette::kGrid, kGridLinePx);
    }
    for (int j = 0; j <= lines_y; ++j) {
        const float y = y0 + static_cast<float>(j) * s;
        add_line(list.floor_lines, {x0, y, 0}, {x1, y, 0}, palette::kGrid, kGridLinePx);
    }
}

void add_boundary_faces(const Scene& scene, const Bounds& w, DrawList& list) {
    for (int face = 0; face < 6; ++face) {
        const FaceMarking marking = scene.faces[static_cast<std::size_t>(face)];
        if (marking == FaceMarking::None) continue;
        const int axis = face / 2;
        const float level = (face % 2) ? w.max[axis] : w.min[axis];
        const int a = (axis + 1) % 3, b = (axis + 2) % 3;
        glm::vec3 corners[4];
        const float ua[4] = {w.min[a], w.max[a], w.max[a], w.min[a]};
        const float ub[4] = {w.min[b], w.min[b], w.max[b], w.max[b]};
        for (int i = 0; i < 4; ++i) {
            corners[i][axis] = level;
            corners[i][a] = ua[i];
            corners[i][b] = ub[i];
        }
        const glm::vec4 fill =
            marking == FaceMarking::Fixed ? palette::kFixedFace : palette::kFreeFace;
        add_quad(list.translucent_triangles, corners, fill);
        const glm::vec4 outline{glm::vec3(fill) * 0.85f, 1.0f};
        for (int i = 0; i < 4; ++i)
            add_line(list.lines, corners[i], corners[(i + 1) % 4], outline, kFaceOutlinePx);
    }
}

void add_origin_star(const Scene& scene, DrawList& list) {
    const BodyView& body = scene.body;
    glm::vec3 at = cell_centre_m(0, 0, 0, body.voxel_size_m);
    for (int v = 0; v < body.voxel_count(); ++v) {
        if (body.voxel_cell[static_cast<std::size_t>(v)] != 0 || body.poses.position_m.empty())
            continue;
        const std::size_t i = static_cast<std::size_t>(v);
        at = {body.poses.position_m[3 * i], body.poses.position_m[3 * i + 1],
              body.poses.position_m[3 * i + 2]};
    }
    list.markers.push_back({at, palette::kStar, 16.0f, MarkerShape::Star});
}

void add_com_trail(const Scene& scene, DrawList& list) {
    const auto& trail = scene.options.com_trail_m;
    for (std::size_t i = 1; i < trail.size(); ++i)
        add_line(list.lines_on_top, trail[i - 1], trail[i], palette::kComTrail, kTrailLinePx);
    for (const auto& p : trail)
        list.bounds.add(p);
    // The current centre of mass: a small dot at the trail's end.
    if (!trail.empty())
        list.markers.push_back({trail.back(), palette::kComTrail, 5.0f, MarkerShape::Dot});
}

}  // namespace

int DrawList::voxel_instance_count() const {
    const auto is_body = [](const BoxInstance& b) {
        return (static_cast<std::uint32_t>(b.flags) & kBoxGhost) == 0;
    };
    int count = 0;
    for (const auto& b : boxes)
        count += is_body(b);
    for (const auto& b : translucent_boxes)
        count += is_body(b);
    return count;
}

Bounds workspace_bounds(const Scene& scene) {
    const auto& body = scene.body;
    const std::array<int, 3> cells =
        scene.workspace[0] > 0 || scene.workspace[1] > 0 || scene.workspace[2] > 0
            ? scene.workspace
            : std::array<int, 3>{body.nx, body.ny, body.nz};
    Bounds b;
    b.add(glm::vec3(0.0f));
    b.add(glm::vec3(static_cast<float>(cells[0] * body.voxel_size_m),
                    static_cast<float>(cells[1] * body.voxel_size_m),
                    static_cast<float>(cells[2] * body.voxel_size_m)));
    return b;
}

DrawList build_draw_list(const Scene& scene) {
    check_body(scene.body);
    DrawList list;
    const SceneOptions& options = scene.options;
    list.workspace_bounds = workspace_bounds(scene);
    list.bounds = list.workspace_bounds;
    add_body(scene, list);
    if (options.show_ghost && scene.ghost_poses) add_ghost(scene, list);
    add_com_trail(scene, list);
    if (options.show_floor) add_floor(scene, list.workspace_bounds, list);
    if (options.show_workspace_box) add_workspace_box(list.workspace_bounds, list);
    if (options.show_boundary_faces) add_boundary_faces(scene, list.workspace_bounds, list);
    if (options.show_origin_star) add_origin_star(scene, list);
    list.axes_gizmo = options.show_axes;
    if (options.color_mode == ColorMode::Scalar && options.show_legend)
        list.legend = Legend{options.color_map, options.scalar_range};
    return list;
}

}  // namespace bhm::render
