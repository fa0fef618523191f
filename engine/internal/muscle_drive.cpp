// Muscle voxels' coefficients and signals (muscle_drive.hpp).
#include "engine/internal/muscle_drive.hpp"

#include <algorithm>
#include <cmath>

#include "engine/internal/model_data.hpp"
#include "engine/muscle.hpp"

namespace bhm::engine {

void build_muscle_drive(Model::Data& d) {
    MuscleDrive& drive = d.muscle;
    const BodySpec& spec = d.spec;
    drive.start_s = spec.actuation.start_s;
    // Which signal each material drives (-1: none); limits::body_spec_problems has already
    // refused a body with more than two, or with sine-active materials beside muscle.
    std::vector<int> signal_of(spec.materials.size(), -1);
    std::vector<bool> used(spec.materials.size(), false);
    for (int v = 0; v < d.voxels; ++v)
        used[d.voxel_material[v] - 1] = true;
    for (std::size_t k = 0; k < spec.materials.size(); ++k) {
        const Material& m = spec.materials[k];
        if (!used[k] || m.actuation_model != ActuationModel::Muscle || !is_active(m)) continue;
        for (int s = 0; s < drive.signals && signal_of[k] < 0; ++s)
            if (muscle::same_signal(drive.signal[s], m.muscle)) signal_of[k] = s;
        if (signal_of[k] < 0 && drive.signals < muscle::kMaxSignals) {
            drive.signal[drive.signals] = m.muscle;
            signal_of[k] = drive.signals++;
        }
    }
    if (drive.signals == 0) return;
    for (int axis = 0; axis < 3; ++axis) {
        drive.axis_signal0[axis].assign(d.stored, 0.0);
        drive.axis_signal1[axis].assign(d.stored, 0.0);
    }
    drive.reach.assign(d.stored, 0.0);
    for (int v = 0; v < d.voxels; ++v) {
        const int k = d.voxel_material[v] - 1;
        const int s = signal_of[k];
        if (s < 0) continue;
        // The voxel's own fibre axis when the body gives one, else its material's: only the
        // axis differs, so a body without per-voxel axes gets the same coefficients as before.
        Material m = spec.materials[k];
        if (!spec.fibre_axis.empty()) {
            const std::uint8_t own = spec.fibre_axis[static_cast<std::size_t>(d.voxel_cell[v])];
            if (own != kMaterialFibreAxis) m.muscle.fibre_axis = own;
        }
        // A controller's amplitude scale (issue 44) shortens the free contraction itself, so the
        // axis strains and the reach stay those of one consistent muscle.
        if (!spec.amplitude_scale.empty())
            m.muscle.contraction_strain *=
                spec.amplitude_scale[static_cast<std::size_t>(d.voxel_cell[v])];
        double mean = 0.0;
        for (int axis = 0; axis < 3; ++axis) {
            const double strain = muscle::axis_strain(m, axis);
            (s == 0 ? drive.axis_signal0 : drive.axis_signal1)[axis][v] = strain;
            mean += strain / 3.0;
        }
        // The voxel's isotropic scale (floor contact, edge springs): the cube of its volume.
        (s == 0 ? d.act_sin : d.act_cos)[v] = mean;
        drive.reach[v] = muscle::largest_scale(m) - 1.0;
        d.any_active = true;
    }
}

void set_muscle_link_rests(Model::Data& d) {
    const MuscleDrive& drive = d.muscle;
    if (drive.signals == 0) return;
    const double L = d.voxel_size_m;
    for (int axis = 0; axis < 3; ++axis) {
        LinkParams& p = d.links[axis];
        const auto& c0 = drive.axis_signal0[axis];
        const auto& c1 = drive.axis_signal1[axis];
        for (int v = 0; v < d.voxels; ++v) {
            if (p.exists[v] == 0.0f) continue;
            const int b = d.plus[axis][v];
            // A link rests at the mean of its ends' sizes along its axis, as for the sine model.
            p.rest_sin[v] = static_cast<float>(0.5 * L * (c0[v] + c0[b]));
            p.rest_cos[v] = static_cast<float>(0.5 * L * (c1[v] + c1[b]));
        }
    }
}

DriveSignals muscle_signals(const MuscleDrive& drive, double t) {
    DriveSignals out;
    const double tau = t - drive.start_s;
    if (drive.signals == 0 || tau < 0.0) return out;
    const muscle::Activation a0 = muscle::activation(drive.signal[0], tau);
    out.c0 = a0.a;
    out.rate0 = a0.rate;
    if (drive.signals > 1) {
        const muscle::Activation a1 = muscle::activation(drive.signal[1], tau);
        out.c1 = a1.a;
        out.rate1 = a1.rate;
    }
    return out;
}

double muscle_axis_scale(const Model::Data& d, int v, int axis, double c0, double c1) {
    const MuscleDrive& drive = d.muscle;
    return 1.0 + drive.axis_signal0[axis][v] * c0 + drive.axis_signal1[axis][v] * c1;
}

}  // namespace bhm::engine
