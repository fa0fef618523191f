#include "evo/experiment/body_spec_of.hpp"

#include <cmath>
#include <numbers>
#include <stdexcept>
#include <utility>

namespace bhm::evo {

namespace {

std::array<int, 3> design_origin(const Experiment& e) {
    const auto& t = e.boundary.enclosure_thickness;
    return {t[0], t[2], t[4]};
}

// SplitMix64 (Steele et al. 2014): a stateless hash, so each cell's phase depends only on the
// seed and the cell, never on visiting order.
std::uint64_t splitmix64(std::uint64_t x) {
    x += 0x9E3779B97F4A7C15ULL;
    x = (x ^ (x >> 30)) * 0xBF58476D1CE4E5B9ULL;
    x = (x ^ (x >> 27)) * 0x94D049BB133111EBULL;
    return x ^ (x >> 31);
}

}  // namespace

Body apply_frame_and_overrides(const Experiment& e, const Body& body) {
    Body out;
    out.size = e.workspace_size;
    out.cells.assign(static_cast<size_t>(out.cell_count()), 0);
    // Per-voxel fibre axes travel with their cells; frame and override cells take the material's.
    const bool fibres = body.fibre.size() == body.cells.size() && !body.fibre.empty();
    if (fibres) out.fibre.assign(out.cells.size(), engine::kMaterialFibreAxis);
    // A controller's phase and amplitude travel with their cells too; frame and override cells
    // are not driven by it (phase 0, amplitude 1).
    const bool controller = body.has_controller() && body.phase.size() == body.cells.size() &&
                            body.amplitude.size() == body.cells.size();
    if (controller) {
        out.phase.assign(out.cells.size(), 0.0f);
        out.amplitude.assign(out.cells.size(), 1.0f);
    }
    const bool workspace_sized = body.size == e.workspace_size;
    const auto origin = workspace_sized ? std::array<int, 3>{0, 0, 0} : design_origin(e);
    for (int z = 0; z < body.size[2]; ++z)
        for (int y = 0; y < body.size[1]; ++y)
            for (int x = 0; x < body.size[0]; ++x) {
                int wx = x + origin[0], wy = y + origin[1], wz = z + origin[2];
                if (wx >= out.size[0] || wy >= out.size[1] || wz >= out.size[2]) continue;
                out.cells[out.index(wx, wy, wz)] = body.cells[body.index(x, y, z)];
                if (fibres) out.fibre[out.index(wx, wy, wz)] = body.fibre[body.index(x, y, z)];
                if (controller) {
                    out.phase[out.index(wx, wy, wz)] = body.phase[body.index(x, y, z)];
                    out.amplitude[out.index(wx, wy, wz)] = body.amplitude[body.index(x, y, z)];
                }
            }
    const auto& t = e.boundary.enclosure_thickness;
    if (e.boundary.enclosure_material > 0) {
        for (int z = 0; z < out.size[2]; ++z)
            for (int y = 0; y < out.size[1]; ++y)
                for (int x = 0; x < out.size[0]; ++x) {
                    bool in_frame = x < t[0] || x >= out.size[0] - t[1] || y < t[2] ||
                                    y >= out.size[1] - t[3] || z < t[4] || z >= out.size[2] - t[5];
                    if (!in_frame) continue;
                    out.cells[out.index(x, y, z)] =
                        static_cast<std::uint8_t>(e.boundary.enclosure_material);
                    if (fibres) out.fibre[out.index(x, y, z)] = engine::kMaterialFibreAxis;
                    if (controller) {
                        out.phase[out.index(x, y, z)] = 0.0f;
                        out.amplitude[out.index(x, y, z)] = 1.0f;
                    }
                }
    }
    for (const auto& o : e.boundary.voxel_overrides) {
        int k = out.index(o.voxel[0], o.voxel[1], o.voxel[2]);
        if (o.kind == OverrideKind::Empty) out.cells[k] = 0;
        if (o.kind == OverrideKind::Material) out.cells[k] = static_cast<std::uint8_t>(o.material);
        if (fibres && o.kind != OverrideKind::Fixed) out.fibre[k] = engine::kMaterialFibreAxis;
        if (controller && o.kind != OverrideKind::Fixed) {
            out.phase[k] = 0.0f;
            out.amplitude[k] = 1.0f;
        }
    }
    return out;
}

engine::BodySpec make_settings_spec(const Experiment& e) {
    engine::BodySpec spec;
    spec.voxel_size_m = e.voxel_size_m;
    spec.environment = e.environment;
    spec.damping.bond_ratio = e.simulation.bond_damping_ratio;
    spec.damping.global_ratio = e.simulation.global_damping_ratio;
    spec.damping.collision_ratio = e.simulation.collision_damping_ratio;
    spec.damping.implicit_sweeps = e.simulation.implicit_damping_sweeps;
    spec.actuation.frequency_hz = e.actuation.frequency_hz;
    spec.actuation.temperature_amplitude_c = e.actuation.temperature_amplitude_c;
    spec.actuation.start_s = e.simulation.settle_s;
    spec.dt_fraction = e.simulation.dt_fraction;
    spec.rotary_inertia_scale = e.simulation.rotary_inertia_scale;
    return spec;
}

std::string experiment_field_of(const std::string& field) {
    static const std::pair<const char*, const char*> kNames[] = {
        {"voxel_size_m", "workspace.voxel_size_m"},
        {"damping.bond_ratio", "simulation.bond_damping_ratio"},
        {"damping.global_ratio", "simulation.global_damping_ratio"},
        {"damping.collision_ratio", "simulation.collision_damping_ratio"},
        {"damping.implicit_sweeps", "simulation.implicit_damping_sweeps"},
        {"dt_fraction", "simulation.dt_fraction"},
        {"rotary_inertia_scale", "simulation.rotary_inertia_scale"},
        {"actuation.start_s", "simulation.settle_s"},
    };
    for (const auto& [spec_name, file_name] : kNames)
        if (field == spec_name) return file_name;
    return field;
}

std::vector<std::uint8_t> held_cells(const Boundary& boundary, std::array<int, 3> size) {
    std::vector<std::uint8_t> held(static_cast<std::size_t>(size[0]) * size[1] * size[2], 0);
    auto index = [&](int x, int y, int z) {
        return static_cast<std::size_t>(x + size[0] * (y + size[1] * z));
    };
    for (int z = 0; z < size[2]; ++z)
        for (int y = 0; y < size[1]; ++y)
            for (int x = 0; x < size[0]; ++x) {
                const int c[3] = {x, y, z};
                bool fixed = false;
                for (int axis = 0; axis < 3; ++axis) {
                    if (boundary.faces[2 * axis] == BoundaryKind::Fixed && c[axis] == 0)
                        fixed = true;
                    if (boundary.faces[2 * axis + 1] == BoundaryKind::Fixed &&
                        c[axis] == size[axis] - 1)
                        fixed = true;
                }
                held[index(x, y, z)] = fixed ? 1 : 0;
            }
    for (const auto& o : boundary.voxel_overrides)
        if (o.kind == OverrideKind::Fixed && o.voxel[0] < size[0] && o.voxel[1] < size[1] &&
            o.voxel[2] < size[2])
            held[index(o.voxel[0], o.voxel[1], o.voxel[2])] = 1;
    return held;
}

engine::BodySpec make_body_spec(const Experiment& e, const Body& framed, std::uint64_t phase_seed) {
    if (framed.cells.size() != static_cast<size_t>(framed.cell_count()))
        throw std::invalid_argument("body cells do not match its size");
    engine::BodySpec spec = make_settings_spec(e);
    spec.nx = framed.size[0];
    spec.ny = framed.size[1];
    spec.nz = framed.size[2];
    spec.material = framed.cells;
    if (framed.fibre.size() == framed.cells.size()) spec.fibre_axis = framed.fibre;
    spec.phase_rad.assign(framed.cells.size(), 0.0f);
    for (const auto& m : e.materials)
        spec.materials.push_back(m.physics);
    for (auto cell : framed.cells)
        if (cell > spec.materials.size())
            throw std::invalid_argument("body uses material " + std::to_string(cell) +
                                        " but only " + std::to_string(spec.materials.size()) +
                                        " are defined");

    spec.fixed = held_cells(e.boundary, framed.size);
    if (framed.has_controller()) {  // an evolved or given controller (issue 44)
        if (framed.phase.size() != framed.cells.size() ||
            framed.amplitude.size() != framed.cells.size())
            throw std::invalid_argument(
                "body controller phase and amplitude do not match its cells");
        spec.phase_rad = framed.phase;
        spec.amplitude_scale = framed.amplitude;
    } else if (e.actuation.phase == PhaseMode::Random)
        for (std::size_t k = 0; k < spec.phase_rad.size(); ++k) {
            double u =
                static_cast<double>(splitmix64(phase_seed ^ splitmix64(k)) >> 11) * 0x1.0p-53;
            spec.phase_rad[k] = static_cast<float>(2.0 * std::numbers::pi * u);
        }
    // A muscle voxel's phase delays its stimulus (engine/muscle.hpp); only a controller sets it
    // (issue 44). actuation.phase and phase_offset_rad stay the sine model's, so a muscle body
    // without a controller keeps the timing it had before delays existed, bit for bit.
    auto muscle = [&](std::size_t k) {
        const auto cell = spec.material[k];
        return cell > 0 &&
               spec.materials[cell - 1].actuation_model == engine::ActuationModel::Muscle;
    };
    for (std::size_t k = 0; k < spec.phase_rad.size(); ++k) {
        if (muscle(k)) {
            if (!framed.has_controller()) spec.phase_rad[k] = 0.0f;
            continue;
        }
        if (e.actuation.phase_offset_rad != 0.0)
            spec.phase_rad[k] =
                static_cast<float>(spec.phase_rad[k] + e.actuation.phase_offset_rad);
    }
    return spec;
}

}  // namespace bhm::evo
