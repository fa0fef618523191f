#include "app/gui/view/scene.hpp"

#include <algorithm>
#include <cmath>
#include <map>

#include <glm/gtc/quaternion.hpp>

#include "app/cli/render_scene.hpp"
#include "app/gui/document/constraint_edits.hpp"
#include "app/gui/session/replay_player.hpp"
#include "evo/experiment/body_spec_of.hpp"

namespace bhm::app::gui {

namespace {

constexpr glm::vec4 kForbiddenColor{0.25f, 0.25f, 0.28f, 0.45f};
constexpr glm::vec4 kFixedMarkerColor{0.18f, 0.72f, 0.30f, 0.55f};
constexpr glm::vec4 kFixedFaceHatch{0.10f, 0.58f, 0.22f, 1.0f};
//! How far outside the workspace a face's tint lies, in voxels (lift_face_tints).
constexpr float kFaceTintLift = 0.05f;

//! Where a face's tint lies along its axis: just outside the workspace, except the bottom face,
//! which lies just above it (the floor is at z = 0 and would hide a tint under it).
float face_tint_level(int axis, bool high, const glm::vec3& workspace_hi, float voxel) {
    if (axis == 2 && !high) return kFaceTintLift * voxel;
    return high ? workspace_hi[axis] + kFaceTintLift * voxel : -kFaceTintLift * voxel;
}

std::array<render::FaceMarking, 6> face_markings(const evo::Boundary& boundary) {
    std::array<render::FaceMarking, 6> faces{};
    for (int f = 0; f < 6; ++f)
        faces[static_cast<std::size_t>(f)] =
            boundary.faces[static_cast<std::size_t>(f)] == evo::BoundaryKind::Fixed
                ? render::FaceMarking::Fixed
                : render::FaceMarking::Free;
    return faces;
}

bool in_frame(const evo::Experiment& e, const std::array<int, 3>& c) {
    const auto& t = e.boundary.enclosure_thickness;
    for (int a = 0; a < 3; ++a) {
        if (c[a] < t[2 * a]) return true;
        if (c[a] >= e.workspace_size[a] - t[2 * a + 1]) return true;
    }
    return false;
}

evo::Body empty_workspace_body(const evo::Experiment& e) {
    evo::Body body;
    body.size = e.workspace_size;
    body.cells.assign(static_cast<std::size_t>(body.cell_count()), 0);
    return body;
}

}  // namespace

std::vector<glm::vec4> material_colors(const evo::Experiment& experiment) {
    return experiment_material_colors(experiment);
}

PainterMaterials painter_materials(const evo::Experiment& experiment) {
    const int m = static_cast<int>(experiment.materials.size());
    return {m + 1, m + 2, m + 3};
}

std::vector<std::uint8_t> painter_occupancy(const evo::Experiment& e, const evo::Body* context) {
    const bool use_context = context && context->size == e.workspace_size;
    const evo::Body framed =
        evo::apply_frame_and_overrides(e, use_context ? *context : empty_workspace_body(e));
    std::vector<std::uint8_t> occupied(framed.cells.size(), 0);
    for (std::size_t i = 0; i < framed.cells.size(); ++i)
        occupied[i] = framed.cells[i] != 0;
    for (const auto& o : e.boundary.voxel_overrides) {
        const auto& v = o.voxel;
        if (v[0] < 0 || v[1] < 0 || v[2] < 0 || v[0] >= framed.size[0] || v[1] >= framed.size[1] ||
            v[2] >= framed.size[2])
            continue;
        occupied[static_cast<std::size_t>(framed.index(v[0], v[1], v[2]))] = 1;
    }
    return occupied;
}

render::Scene workspace_scene(const evo::Experiment& e, const PainterState& painter,
                              const evo::Body* context) {
    const bool use_context = context && context->size == e.workspace_size;
    const evo::Body framed =
        evo::apply_frame_and_overrides(e, use_context ? *context : empty_workspace_body(e));
    const PainterMaterials extra = painter_materials(e);

    // Per cell: the material to draw and whether it is held.
    std::vector<std::uint8_t> material(framed.cells.begin(), framed.cells.end());
    std::vector<std::uint8_t> held(material.size(), 0);
    for (int z = 0; z < framed.size[2]; ++z)
        for (int y = 0; y < framed.size[1]; ++y)
            for (int x = 0; x < framed.size[0]; ++x) {
                const auto i = static_cast<std::size_t>(framed.index(x, y, z));
                // The frame overwrites the outer layers (evo/experiment/body_spec_of.hpp); overrides come after it.
                if (material[i] != 0 && e.boundary.enclosure_material != 0 &&
                    in_frame(e, {x, y, z}) && find_override(e, {x, y, z}) < 0)
                    material[i] = static_cast<std::uint8_t>(extra.frame);
            }
    for (const auto& o : e.boundary.voxel_overrides) {
        const auto& v = o.voxel;
        if (v[0] < 0 || v[1] < 0 || v[2] < 0 || v[0] >= framed.size[0] || v[1] >= framed.size[1] ||
            v[2] >= framed.size[2])
            continue;
        const auto i = static_cast<std::size_t>(framed.index(v[0], v[1], v[2]));
        if (o.kind == evo::OverrideKind::Empty)
            material[i] = static_cast<std::uint8_t>(extra.forbidden);
        if (o.kind == evo::OverrideKind::Fixed) {
            if (material[i] == 0) material[i] = static_cast<std::uint8_t>(extra.fixed);
            held[i] = 1;
        }
    }

    render::Scene scene;
    auto& body = scene.body;
    body.nx = framed.size[0], body.ny = framed.size[1], body.nz = framed.size[2];
    body.voxel_size_m = e.voxel_size_m;
    for (int z = 0; z < framed.size[2]; ++z)
        for (int y = 0; y < framed.size[1]; ++y)
            for (int x = 0; x < framed.size[0]; ++x) {
                const auto i = static_cast<std::size_t>(framed.index(x, y, z));
                if (material[i] == 0 || painter.slice.hides({x, y, z})) continue;
                body.voxel_cell.push_back(static_cast<std::int32_t>(i));
                body.voxel_material.push_back(material[i]);
                body.voxel_fixed.push_back(held[i]);
            }
    body.poses = render::rest_poses(body);
    scene.workspace = e.workspace_size;
    scene.material_colors = material_colors(e);
    scene.material_colors.push_back(render::palette::kEnclosure);
    scene.material_colors.push_back(kForbiddenColor);
    scene.material_colors.push_back(kFixedMarkerColor);
    scene.faces = face_markings(e.boundary);
    scene.options.show_legend = false;
    return scene;
}

namespace {

// The poses of the listed voxels only.
engine::VoxelPoses subset_poses(const engine::VoxelPoses& all, const std::vector<int>& voxels) {
    engine::VoxelPoses out;
    out.time_s = all.time_s;
    out.position_m.reserve(3 * voxels.size());
    out.orientation.reserve(4 * voxels.size());
    out.size_m.reserve(3 * voxels.size());
    for (const int v : voxels) {
        const auto i = static_cast<std::ptrdiff_t>(v);
        out.position_m.insert(out.position_m.end(), all.position_m.begin() + 3 * i,
                              all.position_m.begin() + 3 * i + 3);
        out.orientation.insert(out.orientation.end(), all.orientation.begin() + 4 * i,
                               all.orientation.begin() + 4 * i + 4);
        out.size_m.insert(out.size_m.end(), all.size_m.begin() + 3 * i,
                          all.size_m.begin() + 3 * i + 3);
    }
    return out;
}

}  // namespace

render::Scene simulation_scene(const SimulatedBody& simulated, double t_s, const ViewState& view) {
    const auto& replay = simulated.replay;
    const auto& e = simulated.experiment;
    render::Scene scene;
    auto& body = scene.body;
    body.nx = replay.nx, body.ny = replay.ny, body.nz = replay.nz;
    body.voxel_size_m = replay.voxel_size_m;
    // Only voxels that can be seen: a voxel enclosed on all six faces is hidden by its
    // neighbours (all materials are opaque here), and a software rasterizer pays for every box.
    const bool all = simulated.surface_voxels.empty();
    const std::size_t n = all ? replay.voxel_cell.size() : simulated.surface_voxels.size();
    for (std::size_t k = 0; k < n; ++k) {
        const auto v = all ? k : static_cast<std::size_t>(simulated.surface_voxels[k]);
        body.voxel_cell.push_back(replay.voxel_cell[v]);
        body.voxel_material.push_back(replay.voxel_material[v]);
        body.voxel_fixed.push_back(v < replay.voxel_fixed.size() ? replay.voxel_fixed[v] : 0);
    }
    if (replay.frames.empty()) {
        body.poses = render::rest_poses(body);
    } else {
        const auto poses = engine::pose_at(replay, t_s);
        body.poses = all ? poses : subset_poses(poses, simulated.surface_voxels);
    }
    scene.workspace = e.workspace_size;
    scene.material_colors = material_colors(e);
    scene.faces = face_markings(e.boundary);
    // No translucent face quads over a moving body: they tint it, and where the body touches a
    // face they z-fight with its voxels. Fixed faces are hatched just outside the workspace
    // instead (add_fixed_face_hatch); free faces are the workspace box's edges.
    scene.options.show_boundary_faces = false;
    scene.options.show_edges = view.show_edges;
    scene.options.show_legend = false;
    if (view.color_by != ColorBy::Material && !replay.frames.empty()) {
        // A scalar field over the voxels (displacement, strain, actuation), on the drawn ones.
        const auto field = voxel_scalars(view.color_by, e, replay, frame_index_at(replay, t_s),
                                         simulated.series, simulated.drive);
        scene.options.color_mode = render::ColorMode::Scalar;
        scene.options.voxel_scalar.reserve(n);
        for (std::size_t k = 0; k < n; ++k)
            scene.options.voxel_scalar.push_back(
                field.values[all ? k : static_cast<std::size_t>(simulated.surface_voxels[k])]);
        if (!field.without.empty()) {
            scene.options.voxel_without_scalar.reserve(n);
            for (std::size_t k = 0; k < n; ++k)
                scene.options.voxel_without_scalar.push_back(
                    field.without[all ? k : static_cast<std::size_t>(simulated.surface_voxels[k])]);
        }
        scene.options.scalar_range = field.range;
        scene.options.color_map = field.map;
    }
    if (view.show_trail && !simulated.com_m.empty()) {
        const int last = std::max(0, frame_index_at(replay, t_s));
        scene.options.com_trail_m.assign(simulated.com_m.begin(),
                                         simulated.com_m.begin() + last + 1);
    }
    if (view.show_start_beside && !replay.frames.empty()) {
        scene.ghost_poses = all ? replay.frames.front()
                                : subset_poses(replay.frames.front(), simulated.surface_voxels);
        scene.options.show_ghost = true;
        scene.options.ghost_offset_m = {
            0.0f, static_cast<float>((replay.ny + 1) * replay.voxel_size_m), 0.0f};
    }
    return scene;
}

bool apply_fem_overlay(render::Scene& scene, const FemVerification& v, int load) {
    if (load < 0 || load >= static_cast<int>(v.fem_shape.size()) ||
        load >= static_cast<int>(v.engine_shape.size()))
        return false;
    std::map<int, std::size_t> index_of;
    for (std::size_t k = 0; k < v.voxel_cells.size(); ++k)
        index_of[v.voxel_cells[k]] = k;
    const auto& fem = v.fem_shape[static_cast<std::size_t>(load)];
    const auto& ours = v.engine_shape[static_cast<std::size_t>(load)];
    engine::VoxelPoses body, ghost;
    auto copy = [](const engine::VoxelPoses& from, std::size_t k, engine::VoxelPoses& to) {
        to.position_m.insert(to.position_m.end(), from.position_m.begin() + 3 * k,
                             from.position_m.begin() + 3 * k + 3);
        to.orientation.insert(to.orientation.end(), from.orientation.begin() + 4 * k,
                              from.orientation.begin() + 4 * k + 4);
        to.size_m.insert(to.size_m.end(), from.size_m.begin() + 3 * k,
                         from.size_m.begin() + 3 * k + 3);
    };
    for (const int cell : scene.body.voxel_cell) {
        const auto it = index_of.find(cell);
        if (it == index_of.end() || 3 * it->second + 3 > fem.position_m.size() ||
            3 * it->second + 3 > ours.position_m.size())
            return false;
        copy(ours, it->second, body);
        copy(fem, it->second, ghost);
    }
    scene.body.poses = std::move(body);
    scene.ghost_poses = std::move(ghost);
    scene.options.show_ghost = true;
    scene.options.ghost_offset_m = glm::vec3(0.0f);
    scene.options.com_trail_m.clear();
    scene.options.color_mode = render::ColorMode::Material;  // the replay's fields are not for it
    scene.options.voxel_scalar.clear();
    return true;
}

void add_cell_highlight(render::DrawList& list, const std::array<int, 3>& cell, double voxel_size_m,
                        glm::vec4 color) {
    const float s = static_cast<float>(voxel_size_m);
    const glm::vec3 lo{cell[0] * s, cell[1] * s, cell[2] * s};
    const glm::vec3 hi = lo + glm::vec3(s);
    const glm::vec3 c[8] = {{lo.x, lo.y, lo.z}, {hi.x, lo.y, lo.z}, {hi.x, hi.y, lo.z},
                            {lo.x, hi.y, lo.z}, {lo.x, lo.y, hi.z}, {hi.x, lo.y, hi.z},
                            {hi.x, hi.y, hi.z}, {lo.x, hi.y, hi.z}};
    const int edges[12][2] = {{0, 1}, {1, 2}, {2, 3}, {3, 0}, {4, 5}, {5, 6},
                              {6, 7}, {7, 4}, {0, 4}, {1, 5}, {2, 6}, {3, 7}};
    for (const auto& edge : edges) {
        list.lines.push_back({c[edge[0]], color, 3.0f});
        list.lines.push_back({c[edge[1]], color, 3.0f});
    }
}

void add_posed_voxel_highlight(render::DrawList& list, const engine::VoxelPoses& poses, int voxel,
                               glm::vec4 color) {
    if (voxel < 0 || voxel >= poses.voxel_count()) return;
    const auto i = static_cast<std::size_t>(voxel);
    const glm::vec3 centre{poses.position_m[3 * i], poses.position_m[3 * i + 1],
                           poses.position_m[3 * i + 2]};
    const glm::quat q{poses.orientation[4 * i], poses.orientation[4 * i + 1],
                      poses.orientation[4 * i + 2], poses.orientation[4 * i + 3]};
    const glm::vec3 half = 0.54f * glm::vec3{poses.size_m[3 * i], poses.size_m[3 * i + 1],
                                              poses.size_m[3 * i + 2]};
    glm::vec3 c[8];
    for (int k = 0; k < 8; ++k) {
        const glm::vec3 local{(k & 1) ? half.x : -half.x, (k & 2) ? half.y : -half.y,
                              (k & 4) ? half.z : -half.z};
        c[k] = centre + q * local;
    }
    const int edges[12][2] = {{0, 1}, {2, 3}, {4, 5}, {6, 7}, {0, 2}, {1, 3},
                              {4, 6}, {5, 7}, {0, 4}, {1, 5}, {2, 6}, {3, 7}};
    for (const auto& edge : edges) {
        list.lines_on_top.push_back({c[edge[0]], color, 3.0f});
        list.lines_on_top.push_back({c[edge[1]], color, 3.0f});
    }
}

void add_fixed_face_hatch(render::DrawList& list, const std::array<int, 3>& workspace,
                          double voxel_size_m, evo::Face face) {
    const float s = static_cast<float>(voxel_size_m);
    const glm::vec3 hi{workspace[0] * s, workspace[1] * s, workspace[2] * s};
    const int axis = static_cast<int>(face) / 2;
    // Outside the workspace by a tenth of a voxel: held voxels sit exactly on the face plane.
    const float level = static_cast<int>(face) % 2 ? hi[axis] + 0.1f * s : -0.1f * s;
    const int u = (axis + 1) % 3, v = (axis + 2) % 3;
    auto at = [&](float a, float b) {
        glm::vec3 p;
        p[axis] = level;
        p[u] = a;
        p[v] = b;
        return p;
    };
    const glm::vec4 color = kFixedFaceHatch;
    auto line = [&](glm::vec3 a, glm::vec3 b) {
        list.lines.push_back({a, color, 2.0f});
        list.lines.push_back({b, color, 2.0f});
    };
    line(at(0, 0), at(hi[u], 0));
    line(at(hi[u], 0), at(hi[u], hi[v]));
    line(at(hi[u], hi[v]), at(0, hi[v]));
    line(at(0, hi[v]), at(0, 0));
    // Diagonal hatching, one line per voxel pitch along u + v (a "wall" sign, as in drawings).
    const int n = workspace[static_cast<std::size_t>(u)] + workspace[static_cast<std::size_t>(v)];
    for (int k = 1; k < n; ++k) {
        const float d = static_cast<float>(k) * s;  // the line a + b = d
        const float a0 = std::max(0.0f, d - hi[v]), a1 = std::min(hi[u], d);
        if (a1 > a0) line(at(a0, d - a0), at(a1, d - a1));
    }
}

void add_face_highlight(render::DrawList& list, const std::array<int, 3>& workspace,
                        double voxel_size_m, evo::Face face, glm::vec4 color) {
    const float s = static_cast<float>(voxel_size_m);
    const glm::vec3 hi{workspace[0] * s, workspace[1] * s, workspace[2] * s};
    const int axis = static_cast<int>(face) / 2;
    const bool high = static_cast<int>(face) % 2 != 0;
    const float level = high ? hi[axis] : 0.0f;
    const int u = (axis + 1) % 3, v = (axis + 2) % 3;
    glm::vec3 corner[4];
    const float us[4] = {0.0f, hi[u], hi[u], 0.0f}, vs[4] = {0.0f, 0.0f, hi[v], hi[v]};
    for (int k = 0; k < 4; ++k) {
        corner[k][axis] = level;
        corner[k][u] = us[k];
        corner[k][v] = vs[k];
    }
    // The tint beside the face (lift_face_tints), its outline on the workspace's edges.
    for (int k : {0, 1, 2, 0, 2, 3}) {
        glm::vec3 p = corner[k];
        p[axis] = face_tint_level(axis, high, hi, s);
        list.translucent_triangles.push_back({p, color});
    }
    for (int k = 0; k < 4; ++k) {
        list.lines.push_back({corner[k], glm::vec4(glm::vec3(color), 1.0f), 3.0f});
        list.lines.push_back({corner[(k + 1) % 4], glm::vec4(glm::vec3(color), 1.0f), 3.0f});
    }
}

void lift_face_tints(render::DrawList& list, const std::array<int, 3>& workspace,
                     double voxel_size_m) {
    const float s = static_cast<float>(voxel_size_m);
    const glm::vec3 hi{workspace[0] * s, workspace[1] * s, workspace[2] * s};
    const float tolerance = 1e-4f * s;
    auto& triangles = list.translucent_triangles;
    // The renderer's face tints are quads of six vertices (render::add_boundary_faces).
    for (std::size_t i = 0; i + 6 <= triangles.size(); i += 6) {
        for (int axis = 0; axis < 3; ++axis) {
            for (const bool high : {false, true}) {
                const float level = high ? hi[axis] : 0.0f;
                bool on_face = true;
                for (std::size_t k = i; k < i + 6 && on_face; ++k)
                    on_face = std::fabs(triangles[k].position[axis] - level) <= tolerance;
                if (!on_face) continue;
                for (std::size_t k = i; k < i + 6; ++k)
                    triangles[k].position[axis] = face_tint_level(axis, high, hi, s);
            }
        }
    }
}

}  // namespace bhm::app::gui
