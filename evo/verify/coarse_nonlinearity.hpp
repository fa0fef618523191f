#pragma once
// The FEM's geometrically nonlinear answer estimated from a coarser mesh (a multi-fidelity
// correction): the fine mesh's linear answer plus what geometric nonlinearity changes on a mesh
// of one element per voxel (its nonlinear answer minus its linear one), interpolated to the fine
// nodes by the coarse elements' own shape functions. The nonlinear part of a bending body is a
// large-scale, geometric effect that a coarse mesh resolves, while the fine mesh keeps the
// stiffness of narrow sections; a nonlinear solve iterates tens of times on its mesh, so solving
// it on the coarse one costs a fraction (docs/verify.md, "Linear or nonlinear": measured against
// the fine nonlinear solve). What the evolution loop's checks use; bhm verify solves in full.
#include "evo/verify/ccx_run.hpp"
#include "evo/verify/fem_model.hpp"

namespace bhm::evo {

//! The coarse mesh of a fine one: the same element, one per voxel edge.
FemMeshOptions coarse_mesh_of(const FemMeshOptions& fine);

//! fine_linear plus the coarse nonlinear part at every fine node; fixed nodes stay at 0. Both
//! models must mesh the same voxels (throws std::invalid_argument otherwise, or when `coarse` has
//! more than one element per voxel); a node missing from a block throws std::runtime_error.
NodalDisplacements with_coarse_nonlinearity(const FemModel& fine,
                                            const NodalDisplacements& fine_linear,
                                            const FemModel& coarse,
                                            const NodalDisplacements& coarse_linear,
                                            const NodalDisplacements& coarse_nonlinear);

}  // namespace bhm::evo
