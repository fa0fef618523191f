#include "app/gui/session/body_analysis.hpp"

#include <algorithm>
#include <cmath>
#include <numbers>

#include <glm/geometric.hpp>

#include "engine/muscle.hpp"
#include "evo/experiment/body_spec_of.hpp"

namespace bhm::app::gui {

namespace {

// Coordinates of a lattice cell (x fastest).
std::array<int, 3> cell_coords(const engine::Replay& r, int cell) {
    return {cell % r.nx, (cell / r.nx) % r.ny, cell / (r.nx * r.ny)};
}

glm::vec3 position(const engine::VoxelPoses& f, std::size_t v) {
    return {f.position_m[3 * v], f.position_m[3 * v + 1], f.position_m[3 * v + 2]};
}

glm::vec3 centroid(const engine::VoxelPoses& f, const std::vector<std::size_t>& voxels) {
    glm::vec3 c(0.0f);
    for (const auto v : voxels)
        c += position(f, v);
    return voxels.empty() ? c : c / static_cast<float>(voxels.size());
}

int first_settled_frame(const engine::Replay& r) {
    for (std::size_t k = 0; k < r.frames.size(); ++k)
        if (r.frames[k].time_s >= r.settle_s - 1e-9) return static_cast<int>(k);
    return r.frames.empty() ? -1 : static_cast<int>(r.frames.size()) - 1;
}

}  // namespace

BodyTimeSeries body_time_series(const evo::Experiment& e, const engine::Replay& r,
                                const std::vector<glm::vec3>& com_m) {
    BodyTimeSeries out;
    if (r.frames.empty()) return out;
    const double L = r.voxel_size_m;
    const std::size_t n = r.voxel_cell.size();

    // Base and tip layers (evo/evaluate/fitness.hpp's definition).
    int face = 0;
    for (int f = 0; f < 6; ++f)
        if (e.boundary.faces[static_cast<std::size_t>(f)] == evo::BoundaryKind::Fixed) {
            face = f;
            break;
        }
    const int axis = face / 2;
    const bool from_max = face % 2 == 1;
    int nearest = from_max ? -1 : 1 << 30, farthest = from_max ? 1 << 30 : -1;
    for (std::size_t v = 0; v < n; ++v) {
        const int c = cell_coords(r, r.voxel_cell[v])[static_cast<std::size_t>(axis)];
        nearest = from_max ? std::max(nearest, c) : std::min(nearest, c);
        farthest = from_max ? std::min(farthest, c) : std::max(farthest, c);
    }
    std::vector<std::size_t> base, tip;
    for (std::size_t v = 0; v < n; ++v) {
        const int c = cell_coords(r, r.voxel_cell[v])[static_cast<std::size_t>(axis)];
        if (c == nearest) base.push_back(v);
        if (c == farthest) tip.push_back(v);
    }
    const bool bends = nearest != farthest;

    const int ref = first_settled_frame(r);
    const auto& f0 = r.frames[static_cast<std::size_t>(ref)];
    const glm::vec3 com0 = com_m.empty() ? glm::vec3(0.0f) : com_m[static_cast<std::size_t>(ref)];
    const glm::vec3 tip0 = centroid(f0, tip);
    const glm::vec3 dir0 = tip0 - centroid(f0, base);
    const auto& first = r.frames.front();
    // The colour ranges in double, finite values only, clamped: a replay holding 3.4e38 made them
    // infinite in float, a "-inf to inf" colour bar (issue 41).
    render::ScalarExtent displacement, strain;
    for (std::size_t k = 0; k < r.frames.size(); ++k) {
        const auto& f = r.frames[k];
        out.t_s.push_back(f.time_s);
        const bool measuring = static_cast<int>(k) >= ref;
        const glm::vec3 d = measuring && k < com_m.size() ? com_m[k] - com0 : glm::vec3(0.0f);
        for (int a = 0; a < 3; ++a)
            out.com_vox[static_cast<std::size_t>(a)].push_back(d[a] / L);
        const glm::vec3 t = centroid(f, tip);
        out.tip_vox.push_back(measuring ? glm::length(t - tip0) / L : 0.0);
        double angle = 0.0;
        if (measuring && bends) {
            const glm::vec3 dir = t - centroid(f, base);
            const double c = glm::dot(dir, dir0) / (glm::length(dir) * glm::length(dir0) + 1e-30);
            angle = std::acos(std::clamp(c, -1.0, 1.0)) * 180.0 / std::numbers::pi;
        }
        out.bend_deg.push_back(angle);
        for (std::size_t v = 0; v < n; ++v) {
            displacement.add(
                glm::length(glm::dvec3(position(f, v)) - glm::dvec3(position(first, v))) / L);
            const double volume =
                static_cast<double>(f.size_m[3 * v]) * f.size_m[3 * v + 1] * f.size_m[3 * v + 2];
            strain.add(volume / (L * L * L) - 1.0);
        }
    }
    out.max_displacement_vox = displacement.range(false, 0.0).max;
    out.max_abs_strain = strain.range(false, 0.0).max;
    return out;
}

VoxelScalars voxel_scalars(ColorBy by, const evo::Experiment& e, const engine::Replay& r, int frame,
                           const BodyTimeSeries& series, const VoxelDrive& drive) {
    const std::vector<float>& phases = drive.phase_rad;
    VoxelScalars out;
    const std::size_t n = r.voxel_cell.size();
    out.values.assign(n, 0.0f);
    if (r.frames.empty() || by == ColorBy::Material) return out;
    const auto& f = r.frames[static_cast<std::size_t>(
        std::clamp(frame, 0, static_cast<int>(r.frames.size()) - 1))];
    const auto& first = r.frames.front();
    const float L = static_cast<float>(r.voxel_size_m);
    switch (by) {
        case ColorBy::Displacement:
            for (std::size_t v = 0; v < n; ++v)
                out.values[v] = glm::length(position(f, v) - position(first, v)) / L;
            out.range = {0.0f, std::max(series.max_displacement_vox, 1e-6f)};
            out.map = render::ColorMapName::Sequential;
            out.unit = "voxels";
            break;
        case ColorBy::Strain: {
            for (std::size_t v = 0; v < n; ++v)
                out.values[v] =
                    f.size_m[3 * v] * f.size_m[3 * v + 1] * f.size_m[3 * v + 2] / (L * L * L) -
                    1.0f;
            const float m = std::max(series.max_abs_strain, 1e-6f);
            out.range = {-m, m};
            out.map = render::ColorMapName::Diverging;
            out.unit = "volumetric";
            break;
        }
        case ColorBy::Actuation: {
            // dT = A sin(2 pi f tau + phase), tau = t - settle (engine/world.cpp); a muscle
            // voxel's -a(tau - delay), its activation under its phase's stimulus delay
            // (engine/muscle.hpp; negative: it contracts).
            const double tau = f.time_s - r.settle_s;
            for (std::size_t v = 0; v < n; ++v) {
                const int m = r.voxel_material[v];
                const bool active = m >= 1 && m <= static_cast<int>(e.materials.size()) &&
                                    e.materials[static_cast<std::size_t>(m - 1)].active();
                const float phase = v < phases.size() ? phases[v] : 0.0f;
                const engine::Material* material =
                    active ? &e.materials[static_cast<std::size_t>(m - 1)].physics : nullptr;
                if (material && material->actuation_model == engine::ActuationModel::Muscle) {
                    const engine::Muscle& u = material->muscle;
                    const double delay =
                        engine::muscle::bin_delay_s(u, engine::muscle::delay_bin(phase));
                    out.values[v] =
                        -static_cast<float>(engine::muscle::activation(u, tau - delay).a);
                    continue;
                }
                out.values[v] =
                    active && tau >= 0.0
                        ? static_cast<float>(std::sin(
                              2.0 * std::numbers::pi * e.actuation.frequency_hz * tau + phase))
                        : 0.0f;
            }
            out.range = {-1.0f, 1.0f};
            out.map = render::ColorMapName::Diverging;
            out.unit = "signal";
            break;
        }
        case ColorBy::Phase:
            for (std::size_t v = 0; v < n; ++v) {
                const int m = r.voxel_material[v];
                const bool active = m >= 1 && m <= static_cast<int>(e.materials.size()) &&
                                    e.materials[static_cast<std::size_t>(m - 1)].active();
                out.values[v] = active && v < phases.size() ? phases[v] : 0.0f;
            }
            out.range = {-static_cast<float>(std::numbers::pi),
                         static_cast<float>(std::numbers::pi)};
            out.map = render::ColorMapName::Cyclic;  // -pi and pi are one phase
            out.unit = "rad";
            break;
        case ColorBy::FibreAxis: {
            out.without.assign(n, 0);
            for (std::size_t v = 0; v < n; ++v) {
                const int axis = v < drive.fibre_axis.size() ? drive.fibre_axis[v] : -1;
                out.values[v] = axis >= 0 ? static_cast<float>(axis) : 0.0f;
                out.without[v] = axis >= 0 ? 0 : 1;
            }
            out.range = {0.0f, 2.0f};
            out.map = render::ColorMapName::Axes;
            out.unit = "x  y  z";
            break;
        }
        case ColorBy::Material:
            break;
    }
    return out;
}

VoxelDrive voxel_drive(const evo::Experiment& e, const evo::Body& framed_body,
                       const engine::Replay& r) {
    const auto spec = evo::make_body_spec(e, framed_body, e.evolution.seed);
    VoxelDrive out;
    out.phase_rad.assign(r.voxel_cell.size(), 0.0f);
    out.fibre_axis.assign(r.voxel_cell.size(), -1);
    for (std::size_t v = 0; v < r.voxel_cell.size(); ++v) {
        const auto c = static_cast<std::size_t>(r.voxel_cell[v]);
        if (c < spec.phase_rad.size()) out.phase_rad[v] = spec.phase_rad[c];
        const int m = c < spec.material.size() ? spec.material[c] : 0;
        if (m < 1 || m > static_cast<int>(spec.materials.size())) continue;
        const engine::Material& material = spec.materials[static_cast<std::size_t>(m - 1)];
        if (material.actuation_model != engine::ActuationModel::Muscle) continue;
        const bool own =
            c < spec.fibre_axis.size() && spec.fibre_axis[c] != engine::kMaterialFibreAxis;
        out.fibre_axis[v] =
            static_cast<std::int8_t>(own ? spec.fibre_axis[c] : material.muscle.fibre_axis);
    }
    return out;
}

}  // namespace bhm::app::gui
