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
};

//! The stimulus u in {0, 1} at tau seconds after the actuation starts (0 before).
bool stimulated(const Muscle& m, double tau);
//! The activation at tau seconds after the actuation starts (a = 0, rate 0 for tau <= 0).
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

//! The engine drives at most this many distinct activation signals in one body: each muscle
//! material with its own stimulus and time constants is one; the sine model takes both.
inline constexpr int kMaxSignals = 2;
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

}  // namespace bhm::engine::muscle
