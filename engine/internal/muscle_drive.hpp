#pragma once
// Private to the engine: how Model and World drive muscle voxels (engine/muscle.hpp; issue 43).
//
// Every actuated rest length in the engine is rest_base + c0(t) rest_sin + c1(t) rest_cos: two
// time signals times per-link (and per-voxel: act_sin, act_cos) coefficients, which every pass
// (links, Poisson, edge springs, damping, floor) already reads. The sine model's signals are
// sin and cos of 2 pi f tau. A body of muscle materials uses the same two slots for up to two
// activations a_0(tau), a_1(tau) (one per distinct stimulus and time constants), so no kernel
// changes: only the coefficients differ, anisotropic per axis (the fibre's links shorten by
// contraction_strain a, the others lengthen by nu contraction_strain a), and the signals.
#include <array>
#include <cstdint>
#include <vector>

#include "engine/body_spec.hpp"
#include "engine/model.hpp"
#include "engine/muscle.hpp"

namespace bhm::engine {

struct MuscleDrive {
    int signals = 0;  //!< distinct activation signals (0: no muscle voxel, the sine model)
    std::array<Muscle, 2> signal{};  //!< the stimulus and dynamics of each
    double start_s = 0.0;            //!< the actuation starts here (BodySpec::actuation.start_s)
    //! (stored) per axis: a voxel's strain per unit activation of signal 0 and of signal 1
    //! (0 for voxels that are not muscle)
    std::array<std::vector<double>, 3> axis_signal0, axis_signal1;
    std::vector<double> reach;  //!< (stored) largest |size - 1| of a voxel's links, 0 if none

    //! Delayed stimuli (issue 44): set when some muscle voxel's controller phase falls in a delay
    //! bin other than 0 (muscle::delay_bin). The activations then differ voxel by voxel, not as
    //! the two signals above, so the World keeps its own copy of the model data and rewrites its
    //! actuated coefficients every step (write_delayed_drive); otherwise all of this is empty
    //! and a body runs exactly as before.
    bool delayed = false;
    struct DelayedSignal {
        int source = 0;        //!< which of `signal`
        int bin = 0;           //!< its delay bin
        double delay_s = 0.0;  //!< muscle::bin_delay_s
    };
    std::vector<DelayedSignal> delayed_signals;  //!< the distinct (signal, bin) pairs in use
    //! (stored) a voxel's entry in delayed_signals, -1 for a voxel that is not muscle
    std::vector<std::int16_t> voxel_signal;
};

//! At most this many delayed signals: kMaxSignals stimuli x kDelayBins bins each.
inline constexpr int kMaxDelayedSignals = muscle::kMaxSignals * muscle::kDelayBins;

//! The two signals and their rates at time t (all zero before the actuation starts).
struct DriveSignals {
    double c0 = 0.0, c1 = 0.0, rate0 = 0.0, rate1 = 0.0;
};

//! After the per-voxel loop of Model::build: finds the muscle signals, fills the per-axis
//! coefficients (along each voxel's own fibre axis, BodySpec::fibre_axis, else its material's), and
//! sets a muscle voxel's isotropic act_sin / act_cos (floor contact, edge springs) to its mean axis
//! strain, and any_active.
void build_muscle_drive(Model::Data& d);
//! After the links are built: the rest-length coefficients of every link with a muscle end.
void set_muscle_link_rests(Model::Data& d);
DriveSignals muscle_signals(const MuscleDrive& drive, double t);
//! A voxel's size along `axis` over L at signals (c0, c1): 1 + its axis strain.
double muscle_axis_scale(const Model::Data& d, int v, int axis, double c0, double c1);

//! The activations (and rates) of a delayed body's signals at time t, one per delayed_signals
//! entry: muscle::activation(signal, tau - delay).
struct DelayedActivations {
    std::array<double, kMaxDelayedSignals> a{}, rate{};
    double of(const MuscleDrive& drive, int v) const {
        const int s = drive.voxel_signal[static_cast<std::size_t>(v)];
        return s < 0 ? 0.0 : a[static_cast<std::size_t>(s)];
    }
};
DelayedActivations delayed_activations(const MuscleDrive& drive, double t);
//! A delayed body's voxel size along `axis` over L at time t's activations.
double delayed_axis_scale(const Model::Data& d, int v, int axis, const DelayedActivations& act);
//! A delayed body (drive.delayed) at time t: writes into `own`, the World's copy of `model`, each
//! link's actuated rest (rest_sin, m) and its rate (rest_cos, m/s) and each voxel's isotropic
//! strain (act_sin; act_cos 0, and the edge springs' copies), so that every pass, read with the
//! signals (sin, cos, rate_sin, rate_cos) = (1, 0, 0, 1), sees each voxel's own activation.
//! Allocates nothing.
void write_delayed_drive(const Model::Data& model, Model::Data& own, double t);

}  // namespace bhm::engine
