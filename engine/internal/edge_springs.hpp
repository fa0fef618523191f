#pragma once
// Private to the engine: springs across shared voxel edges.
//
// The lattice joins face neighbours only. Where two voxels share just an edge (face-diagonal
// neighbours) and both voxels between them are softer than either (a checkerboard, a staircase of
// stiff voxels in a soft matrix), the continuum joins them along that edge and carries load from
// one to the other there; the face lattice routes it through the soft voxels only and is far too
// soft (a 10x checkerboard +47 % against CalculiX extrapolated to zero element size,
// docs/physics.md). An edge spring joins the two voxels at the two Gauss points of their shared
// edge, so the pair resists relative translation and rotation about axes across the edge, as a
// line contact does, and turns freely about the edge itself.
//
// Stiffness per unit length of edge: two terms in series, the stiff phase's
// kEdgeStiffPhase (E_end - E_bridge), which vanishes as the contrast goes to 1 (where the face
// lattice is already right), and the soft wedge's kEdgeSoftWedge E_bridge beside the edge, which
// bounds it at high contrast; E_end is the two voxels' moduli in series, E_bridge the stiffer
// bridge's. Across the edge times 1 / (1 - nu^2) (the cross-section of a line contact is in plane
// strain), along it times 1 / (1 + nu) (2 G / E); nu the bridge's, at nu = 0 both are 1. The two
// constants are fitted to CalculiX on the 12x4x4 checkerboard, extrapolated to zero element size:
// contrasts 3 and 10 (nu 0, 0.35, 0.49) and 30 (docs/physics.md, "Springs across edges").
#include "engine/internal/model_data.hpp"
#include "engine/internal/world_state.hpp"

namespace bhm::engine {

inline constexpr double kEdgeStiffPhase = 0.078;
inline constexpr double kEdgeSoftWedge = 4.68;

//! Fills d.edge_springs (after the voxels' masses) and raises max_omega2 to their stiffest mode.
void build_edge_springs(Model::Data& d, double& max_omega2);

//! Sets the springs' bond damping once the step d.dt_s is known.
void finish_edge_springs(Model::Data& d);

//! The springs' loads before the voxel pass integrates: their forces, with the external force,
//! into scratch.force (the voxel pass's applied force, so static friction weighs them too), their
//! moments as spin increments dt M / I (symplectic Euler, as adding M to the voxels' moment sums).
//! Not called without springs.
void edge_pass(const Model::Data& d, VoxelState& s, EdgeScratch& scratch, double sin_t,
               double cos_t);

}  // namespace bhm::engine
