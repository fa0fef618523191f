#pragma once
// The muscle actuation model (issue 43; docs/physics.md, "Muscle actuation"): what a muscle
// material's stimulus is at time tau after the actuation starts, and its activation a(tau) in
// [0, 1] through first-order activation dynamics (Zajac 1989):
//
//     da/dt = (1 - a) / rise_s   while stimulated (u = 1),
//     da/dt = -a / decay_s       otherwise (u = 0),          a(0) = 0.
//
// u(tau) is a rectangular pulse train: pulses of pulse_width_s every 1 / frequency_hz, in
// bursts of train_on_s separated by train_off_s of rest (train_off_s = 0: one endless train;
// spontaneous beating is such a train). Every stimulated or resting stretch maps a linearly
// (an affine map), so a(tau) is evaluated exactly, in O(1), from the maps of one pulse period and
// one burst raised to the number elapsed: no state, the same value at any tau, whichever step
// asks.
//
// Optional fatigue (muscle.fatigue_s > 0; off by default): the force a stimulus raises fades
// while it goes on and comes back at rest. The activation the voxel takes is a(tau) f(tau), with
// the force left f following
//
//     df/dt = -(f - floor) / fatigue_s   while stimulated,
//     df/dt = (1 - f) / recovery_s       otherwise,          f(0) = 1,
//
// the first-order fitness model of Riener, Quintern & Schmidt (1996, J Biomech 29:1157) driven by
// the stimulus u instead of the activation, so that f too is affine per stretch and evaluated by
// the same maps, exactly and without state (a phenomenological model: it has one time constant
// each way, not Ding et al.'s (2000) stimulation-pattern dependence). It never repeats within a
// fatiguing stimulus, so a fatiguing body is not periodic (evo/evaluate/periodic_end.hpp).
//
// The voxel's active strain is along the fibre -contraction_strain x a(tau) and across it
// +nu x contraction_strain x a(tau): the strain a free voxel takes under an active tension
// E x contraction_strain x a along its fibres (the active-stress model of Hunter et al. 1998),
// applied as an anisotropic rest length of the links.
#include <string>
#include <vector>

#include "engine/body_spec.hpp"

namespace bhm::engine::muscle {

//! Activation and its rate at one time.
struct Activation {
    double a = 0.0;     //!< activation in [0, 1]
    double rate = 0.0;  //!< da/dtau (1/s)
    bool stimulated = false;
    double fatigue = 1.0;  //!< f, the force left (a includes it); 1 without fatigue
};

//! Whether the muscle fatigues (fatigue_s > 0 and recovery_s > 0).
bool fatigues(const Muscle& m);
//! The stimulus u in {0, 1} at tau seconds after the actuation starts (0 before).
bool stimulated(const Muscle& m, double tau);
//! The activation at tau seconds after the actuation starts (a = 0, rate 0 for tau <= 0),
//! times the force left under fatigue.
Activation activation(const Muscle& m, double tau);

//! The free strain of a fully activated voxel of material m along lattice axis `axis`:
//! -contraction_strain along the fibre, +nu contraction_strain across it.
double axis_strain(const Material& m, int axis);
//! Largest size scale of a muscle voxel's links over its activation, 1 + max(0, nu) strain
//! (across the fibre; along it the links only shorten).
double largest_scale(const Material& m);

//! Problems of a material's muscle fields (fields named "muscle.rise_s", ..., or "cte_per_c");
//! empty for a sine material.
struct Problem {
    std::string field;
    std::string message;
};
std::vector<Problem> material_problems(const Material& m);

//! The engine drives at most this many distinct stimuli in one body: each muscle material with
//! its own stimulus and time constants is one; the sine model takes both.
inline constexpr int kMaxSignals = 2;

//! The period the stimulus repeats with (s): a burst and its rest for a scheduled pulse train,
//! one pulse period (1 / frequency_hz) for an endless train or beating. A voxel's controller
//! phase delays its stimulus by a fraction of it (issue 44).
double stimulus_period_s(const Muscle& m);
//! A muscle voxel's controller phase (BodySpec::phase_rad) delays its stimulus by
//! bin / kDelayBins of the stimulus period, bin = the phase's nearest 2 pi / kDelayBins step
//! (wrapped onto [0, kDelayBins)): phase 0 (and 2 pi) is bin 0, no delay, today's timing. The
//! quantisation keeps the signals a step evaluates to at most kMaxSignals x kDelayBins; its error
//! is at most half a bin, period / (2 kDelayBins), in time (docs/physics.md, "Muscle actuation").
inline constexpr int kDelayBins = 16;
int delay_bin(double phase_rad);
//! The delay of bin `bin` (s): bin / kDelayBins x stimulus_period_s(m).
double bin_delay_s(const Muscle& m, int bin);
//! Whether two muscle materials share one activation signal (the same stimulus and dynamics).
bool same_signal(const Muscle& a, const Muscle& b);
//! Problems of a palette: a body may not mix sine-active and muscle materials, nor hold more than
//! kMaxSignals distinct muscle signals ("materials[k].actuation_model", ...). Only the materials
//! the lattice uses count when `used` is given (one flag per material).
std::vector<Problem> palette_problems(const std::vector<Material>& materials,
                                      const std::vector<bool>* used = nullptr);

//! Largest and smallest values a muscle field may take (the field table quotes them).
inline constexpr double kMaxContractionStrain = 0.6;  //!< the actuation envelope (limits.hpp)
inline constexpr double kMinTimeConstantS = 1e-4;
inline constexpr double kMaxTimeConstantS = 100.0;
inline constexpr double kMaxStimulusFrequencyHz = 1000.0;
inline constexpr double kMaxTrainS = 1e5;
//! Longest fatigue or recovery time constant (an hour: tissue tires over seconds to minutes).
inline constexpr double kMaxFatigueS = 3600.0;

}  // namespace bhm::engine::muscle
