#include "app/cli/render_scene.hpp"

#include <algorithm>
#include <cmath>
#include <stdexcept>

#include "render/replay_view.hpp"

namespace bhm::app {

namespace {

bool in_frame_layers(const evo::Experiment& e, const std::array<int, 3>& c) {
    const auto& t = e.boundary.enclosure_thickness;
    for (int a = 0; a < 3; ++a) {
        const auto i = static_cast<std::size_t>(a);
        if (c[i] < t[2 * i] || c[i] >= e.workspace_size[i] - t[2 * i + 1]) return true;
    }
    return false;
}

render::Scene scene_frame(const evo::Experiment& experiment) {
    render::Scene scene;
    scene.workspace = experiment.workspace_size;
    scene.material_colors = render_material_colors(experiment);
    scene.faces = render_face_markings(experiment);
    scene.options.show_floor = experiment.environment.floor;
    return scene;
}

}  // namespace

std::vector<glm::vec4> experiment_material_colors(const evo::Experiment& experiment) {
    std::vector<glm::vec4> colors;
    for (const auto& m : experiment.materials) {
        if (m.has_color)
            colors.emplace_back(m.color[0], m.color[1], m.color[2], 1.0f);
        else
            colors.push_back(m.active() ? render::palette::kActive : render::palette::kPassive);
    }
    return colors;
}

std::vector<glm::vec4> render_material_colors(const evo::Experiment& experiment) {
    std::vector<glm::vec4> colors = experiment_material_colors(experiment);
    colors.push_back(render::palette::kEnclosure);
    return colors;
}

std::array<render::FaceMarking, 6> render_face_markings(const evo::Experiment& experiment) {
    std::array<render::FaceMarking, 6> marks{};
    const auto& faces = experiment.boundary.faces;
    for (std::size_t f = 0; f < 6; ++f) {
        const std::size_t opposite = f ^ 1u;  // x- <-> x+, y- <-> y+, z- <-> z+
        if (faces[f] == evo::BoundaryKind::Fixed)
            marks[f] = render::FaceMarking::Fixed;
        else if (faces[opposite] == evo::BoundaryKind::Fixed)
            marks[f] = render::FaceMarking::Free;
    }
    return marks;
}

void mark_enclosure_voxels(const evo::Experiment& experiment, render::BodyView& body) {
    const int enclosure = experiment.boundary.enclosure_material;
    if (enclosure <= 0) return;
    const auto frame_index = static_cast<std::uint8_t>(experiment.materials.size() + 1);
    for (int v = 0; v < body.voxel_count(); ++v) {
        auto& material = body.voxel_material[static_cast<std::size_t>(v)];
        if (material == enclosure && in_frame_layers(experiment, body.voxel_coords(v)))
            material = frame_index;
    }
}

render::Scene rest_scene(const evo::Experiment& experiment, const engine::BodySpec& spec) {
    render::Scene scene = scene_frame(experiment);
    scene.body = render::body_view_from_spec(spec);
    mark_enclosure_voxels(experiment, scene.body);
    return scene;
}

ScalarColoring parse_scalar_coloring(const std::string& name) {
    if (name == "material") return ScalarColoring::Material;
    if (name == "displacement") return ScalarColoring::Displacement;
    if (name == "strain") return ScalarColoring::Strain;
    if (name == "phase") return ScalarColoring::Phase;
    throw std::invalid_argument("unknown colouring '" + name +
                                "' (material, displacement, strain, phase)");
}

render::Scene replay_scene(const evo::Experiment& experiment, const engine::Replay& replay,
                           double time_s, const ReplaySceneOptions& options) {
    const auto& w = experiment.workspace_size;
    if (replay.nx != w[0] || replay.ny != w[1] || replay.nz != w[2])
        throw std::invalid_argument("replay lattice " + std::to_string(replay.nx) + "x" +
                                    std::to_string(replay.ny) + "x" + std::to_string(replay.nz) +
                                    " is not the experiment's workspace " + std::to_string(w[0]) +
                                    "x" + std::to_string(w[1]) + "x" + std::to_string(w[2]));
    render::Scene scene = scene_frame(experiment);
    scene.body = render::body_view_from_replay(replay);
    mark_enclosure_voxels(experiment, scene.body);
    if (replay.frames.empty()) return scene;
    const auto sampling = options.interpolate ? engine::PoseSampling::Interpolate
                                              : engine::PoseSampling::NearestBefore;
    scene.body.poses = engine::pose_at(replay, time_s, sampling);
    if (options.ghost) {
        scene.ghost_poses = replay.frames.front();
        scene.options.show_ghost = true;
        if (options.ghost_beside) {
            const int axis = options.ghost_axis == 0 ? 0 : 1;
            const int cells = axis == 0 ? replay.nx : replay.ny;
            scene.options.ghost_offset_m[axis] =
                static_cast<float>((cells + 1) * replay.voxel_size_m);
        }
    }
    if (options.trail) {
        std::vector<double> density;
        for (const auto& material : experiment.materials)
            density.push_back(material.physics.density_kg_m3);
        scene.options.com_trail_m = render::centre_of_mass_trail(
            replay, time_s, engine::voxel_mass_weights(replay, density));
    }
    return scene;
}

void apply_scalar_coloring(render::Scene& scene, ScalarColoring coloring,
                           const engine::VoxelPoses* rest_poses,
                           const std::vector<float>* cell_phase_rad) {
    auto& options = scene.options;
    const auto& body = scene.body;
    switch (coloring) {
        case ScalarColoring::Material:
            options.color_mode = render::ColorMode::Material;
            return;
        case ScalarColoring::Displacement: {
            // Shown in voxel lengths, the unit of the paper's fitness figures.
            const engine::VoxelPoses lattice = render::rest_poses(body);
            options.voxel_scalar =
                render::voxel_displacement_m(body.poses, rest_poses ? *rest_poses : lattice);
            render::ScalarExtent extent;
            for (float& d : options.voxel_scalar) {
                extent.add(static_cast<double>(d) / body.voxel_size_m);
                d = static_cast<float>(static_cast<double>(d) / body.voxel_size_m);
            }
            options.scalar_range = extent.range(false, 1.0);
            options.color_map = render::ColorMapName::Sequential;
            break;
        }
        case ScalarColoring::Strain: {
            options.voxel_scalar = render::voxel_volume_strain(body.poses, body.voxel_size_m);
            render::ScalarExtent extent;
            for (float s : options.voxel_scalar)
                extent.add(s);
            options.scalar_range = extent.range(true, 0.1);
            options.color_map = render::ColorMapName::Diverging;
            break;
        }
        case ScalarColoring::Phase: {
            if (!cell_phase_rad)
                throw std::invalid_argument("phase colouring needs the body's per-cell phases");
            options.voxel_scalar.clear();
            for (int v = 0; v < body.voxel_count(); ++v) {
                const auto cell =
                    static_cast<std::size_t>(body.voxel_cell[static_cast<std::size_t>(v)]);
                const float phase = cell < cell_phase_rad->size() ? (*cell_phase_rad)[cell] : 0.0f;
                const float two_pi = 6.28318531f;
                options.voxel_scalar.push_back(phase - two_pi * std::floor(phase / two_pi));
            }
            options.scalar_range = {0.0f, 6.28318531f};
            options.color_map = render::ColorMapName::Cyclic;
            break;
        }
    }
    options.color_mode = render::ColorMode::Scalar;
}

render::ScalarRange replay_scalar_range(const engine::Replay& replay, ScalarColoring coloring) {
    // In double, finite values only, clamped (render::ScalarExtent): a replay holding 3.4e38 gave
    // an infinite largest value and a "-inf to inf" scale (issue 41).
    render::ScalarExtent extent;
    for (const auto& frame : replay.frames) {
        if (coloring == ScalarColoring::Displacement) {
            for (float d : render::voxel_displacement_m(frame, replay.frames.front()))
                extent.add(static_cast<double>(d) / replay.voxel_size_m);
        } else if (coloring == ScalarColoring::Strain) {
            for (float e : render::voxel_volume_strain(frame, replay.voxel_size_m))
                extent.add(e);
        }
    }
    switch (coloring) {
        case ScalarColoring::Displacement:
            return extent.range(false, 1.0);
        case ScalarColoring::Strain:
            return extent.range(true, 0.1);
        case ScalarColoring::Phase:
            return {0.0f, 6.28318531f};
        case ScalarColoring::Material:
        default:
            return {0.0f, 1.0f};
    }
}

}  // namespace bhm::app
