#pragma once
// Private to the engine: the implicit bond damping (BodySpec::damping.implicit_sweeps > 0).
//
// The bond damping is Rayleigh damping C = beta K of every link. Explicit (velocity-lagged, in the
// link pass) it bounds the step: for one mode, A = beta mu dt and B = mu dt^2, the recurrence is
// stable only while 2 A + B < 4. Implicit, the velocity after the step solves
//     (M + dt C) v = M v*,   v* = the velocity after the elastic and every other force,
// which damps every mode by a factor in (0, 1], stable for any beta up to the undamped B < 4.
//
// It is solved in link space: the unknowns are each link's damping rates g = beta B v (the
// extension rate and the two ends' rotation rates relative to the link frame, B the rate map of
// link_kinematics.hpp), kept per link from sweep to sweep and step to step (LinkScratch's
// damp_extension, damp_turn_neg / _pos). A sweep relaxes them toward the rates of the current
// velocities, g <- g + s (beta B v - g), s = 1 / (1 + dt max(P_a, P_b)) per link
// (LinkParams::damp_relax), P a voxel's sum over its links of a bound on each link's damping rate
// (link_damping_rate_bound in model.cpp), and the voxels then take v = v* - dt M^-1 B^T K g, the
// beam loads of g at the current chord. The splitting converges: in the inner product of
// (beta K)^-1 the operator I + dt beta K B M^-1 B^T is self-adjoint, and twice the diagonal
// 1 + dt max(P_a, P_b) bounds its weighted row sum 1 + dt (P_a + P_b). Because each link's loads
// are equal and opposite and balanced in moment, a free body keeps its linear and angular
// momentum to float rounding, as with the elastic loads (a per-voxel Jacobi factor scales the two
// ends' shares differently: a free body drifted by 0.2 % of its internal momentum in 0.2 s).
// The sweeps start from v* plus the last step's damping change v - v* (warm), and g from the last
// step's: the smooth modes, whose damping changes little from step to step, start nearly
// converged, and the fast ones, for which the start is wrong, are the ones a sweep converges in
// one go (factor (d - dt mu) / (1 + d) per sweep, d = dt max(P_a, P_b)). docs/physics.md,
// "Damping and the step".
//
// A sweep is a pass over the links (C v from the velocities: beta times the beam loads of the
// deformation rate, in the same link frame the elastic pass used, whose chord is unchanged since
// positions move only after the last sweep) and a gather per voxel in the fixed order of the
// voxel pass: no atomics, no allocation, bit-identical results.
#include "engine/internal/model_data.hpp"
#include "engine/internal/world_state.hpp"

namespace bhm::engine {

//! The damping loads -C v of the current velocities for the links of one axis, written to the
//! scratch's force and moment arrays (the voxel pass has gathered the elastic loads from them).
//! With `poisson` the chords come from its scratch, as in link_pass. The rest lengths change at
//! rate_sin * rest_sin + rate_cos * rest_cos (the time derivatives of sin_t and cos_t).
void damping_link_pass(const Model::Data& model, const VoxelState& voxels, LinkScratch& scratch,
                       const PoissonScratch* poisson, int axis, float sin_t, float cos_t,
                       float rate_sin, float rate_cos);

}  // namespace bhm::engine
