#pragma once
// Private to the engine: the implicit bond damping (BodySpec::damping.implicit_sweeps > 0).
//
// The bond damping is Rayleigh damping C = beta K of every link. Explicit (velocity-lagged, in the
// link pass) it bounds the step: for one mode, A = beta mu dt and B = mu dt^2, the recurrence is
// stable only while 2 A + B < 4. Implicit, the velocity after the step solves
//     (M + dt C) v = M v*,   v* = the velocity after the elastic and every other force,
// which damps every mode by a factor in (0, 1], stable for any beta up to the undamped B < 4. It
// is solved by Jacobi sweeps with the diagonal D = M + dt P, P = m sum over the voxel's links of
// a bound on each link's damping rate (Model::Data::jacobi_lin / jacobi_rot), so P - C is
// positive semidefinite. Sweep: v <- v - D^-1 (M (v - v*) + dt C v). Started from v* (cold), one
// sweep damps every mode by a factor in (0, 1] but a smooth one by only 1 / (1 + d), d = dt P / m,
// of the exact amount, each further sweep converging by d / (1 + d). The sweeps start instead from
// v* plus the last step's damping change v - v* (warm): the smooth modes, whose damping changes
// little from step to step, start nearly converged, and the fast ones, for which the start is
// wrong, are the ones a sweep converges in one go. Per mode, with A = beta mu dt, B = mu dt^2 and
// any 0 < A <= d, one warm sweep is stable for B < 4.0 like the cold one (the eigenvalues of the
// three-variable recurrence of x, v and the kept change). docs/physics.md, "Damping and the step".
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
