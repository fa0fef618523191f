// Muscle voxels' coefficients and signals (muscle_drive.hpp).
#include "engine/internal/muscle_drive.hpp"

#include <algorithm>
#include <cmath>

#include "engine/internal/model_data.hpp"
#include "engine/muscle.hpp"

namespace bhm::engine {

namespace {

// A muscle voxel's controller phase as a delay bin of its stimulus (muscle::delay_bin); the
// table of distinct (signal, bin) pairs only when some bin is not 0.
void build_delays(Model::Data& d, const std::vector<int>& signal_of) {
    MuscleDrive& drive = d.muscle;
    const BodySpec& spec = d.spec;
    if (spec.phase_rad.empty()) return;
    auto bin_of = [&](int v) {
        return muscle::delay_bin(spec.phase_rad[static_cast<std::size_t>(d.voxel_cell[v])]);
    };
    bool any = false;
    for (int v = 0; v < d.voxels && !any; ++v)
        any = signal_of[d.voxel_material[v] - 1] >= 0 && bin_of(v) != 0;
    if (!any) return;
    drive.delayed = true;
    drive.voxel_signal.assign(d.stored, -1);
    // (signal, bin) -> entry; at most kMaxSignals x kDelayBins, so the table never overflows.
    std::array<int, kMaxDelayedSignals> entry_of;
    entry_of.fill(-1);
    for (int v = 0; v < d.voxels; ++v) {
        const int s = signal_of[d.voxel_material[v] - 1];
        if (s < 0) continue;
        const int bin = bin_of(v);
        int& e = entry_of[static_cast<std::size_t>(s * muscle::kDelayBins + bin)];
        if (e < 0) {
            e = static_cast<int>(drive.delayed_signals.size());
            drive.delayed_signals.push_back(
                {s, bin, muscle::bin_delay_s(drive.signal[static_cast<std::size_t>(s)], bin)});
        }
        drive.voxel_signal[static_cast<std::size_t>(v)] = static_cast<std::int16_t>(e);
    }
}

// A voxel's strain along `axis` per unit of its own activation (only one of the two signals'
// coefficients is set for a muscle voxel).
double axis_coefficient(const MuscleDrive& drive, int axis, int v) {
    return drive.axis_signal0[axis][v] + drive.axis_signal1[axis][v];
}

}  // namespace

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
    build_delays(d, signal_of);
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

DelayedActivations delayed_activations(const MuscleDrive& drive, double t) {
    DelayedActivations out;
    const double tau = t - drive.start_s;
    if (tau < 0.0) return out;
    for (std::size_t e = 0; e < drive.delayed_signals.size(); ++e) {
        const MuscleDrive::DelayedSignal& s = drive.delayed_signals[e];
        const muscle::Activation a =
            muscle::activation(drive.signal[static_cast<std::size_t>(s.source)], tau - s.delay_s);
        out.a[e] = a.a;
        out.rate[e] = a.rate;
    }
    return out;
}

double delayed_axis_scale(const Model::Data& d, int v, int axis, const DelayedActivations& act) {
    return 1.0 + axis_coefficient(d.muscle, axis, v) * act.of(d.muscle, v);
}

void write_delayed_drive(const Model::Data& model, Model::Data& own, double t) {
    const MuscleDrive& drive = model.muscle;
    const DelayedActivations act = delayed_activations(drive, t);
    auto rate_of = [&](int v) {
        const int s = drive.voxel_signal[static_cast<std::size_t>(v)];
        return s < 0 ? 0.0 : act.rate[static_cast<std::size_t>(s)];
    };
    const double L = model.voxel_size_m;
    for (int axis = 0; axis < 3; ++axis) {
        const LinkParams& p = model.links[axis];
        LinkParams& q = own.links[axis];
        for (int v = 0; v < model.voxels; ++v) {
            if (p.exists[v] == 0.0f) continue;
            const int b = model.plus[axis][v];
            const double kv = axis_coefficient(drive, axis, v),
                         kb = axis_coefficient(drive, axis, b);
            // As set_muscle_link_rests: the link rests at the mean of its ends' sizes.
            q.rest_sin[v] =
                static_cast<float>(0.5 * L * (kv * act.of(drive, v) + kb * act.of(drive, b)));
            q.rest_cos[v] = static_cast<float>(0.5 * L * (kv * rate_of(v) + kb * rate_of(b)));
        }
    }
    for (int v = 0; v < model.voxels; ++v) {
        // The isotropic (mean) strain per unit activation sits in act_sin or act_cos.
        own.act_sin[v] = (model.act_sin[v] + model.act_cos[v]) * act.of(drive, v);
        own.act_cos[v] = 0.0;
    }
    Model::Data::EdgeSprings& e = own.edge_springs;
    for (int n = 0; n < e.size(); ++n) {
        e.act_sin_a[n] = static_cast<float>(own.act_sin[e.a[n]]);
        e.act_sin_b[n] = static_cast<float>(own.act_sin[e.b[n]]);
        e.act_cos_a[n] = e.act_cos_b[n] = 0.0f;
    }
}

double muscle_axis_scale(const Model::Data& d, int v, int axis, double c0, double c1) {
    const MuscleDrive& drive = d.muscle;
    return 1.0 + drive.axis_signal0[axis][v] * c0 + drive.axis_signal1[axis][v] * c1;
}

}  // namespace bhm::engine
