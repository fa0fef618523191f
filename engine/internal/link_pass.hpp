#pragma once
// Private to the engine: the first pass of a step. For every link slot of one lattice axis,
// computes the beam forces and moments on both ends in world coordinates and stores them in the
// link's scratch arrays (the voxel pass gathers them). No voxel is written: no atomics needed.
#include <string>

#include "engine/internal/model_data.hpp"
#include "engine/internal/world_state.hpp"

namespace bhm::engine {

//! Runs the link pass of one axis; sin_t and cos_t modulate the rest lengths of actuated links
//! (rest = base + sin_t * rest_sin + cos_t * rest_cos). With `poisson` (the coupling is on and
//! poisson_pass has run this step) the rest length also takes the Poisson shift, and the chords
//! come from scratch (poisson.hpp). Returns the
//! number of links that are unhealthy: stretched past one lattice length L, shorter than L / 10,
//! sheared past 120 degrees, or non-finite (the step must then not be committed).
int link_pass(const Model::Data& model, const VoxelState& voxels, LinkScratch& scratch,
              const PoissonScratch* poisson, int axis, float sin_t, float cos_t);

//! Index of the first unhealthy link slot of an axis (after link_pass reported one), or -1.
int first_bad_link(const Model::Data& model, const VoxelState& voxels, const LinkScratch& scratch,
                   int axis, float sin_t, float cos_t);

//! Length, actuated rest length (in lattice lengths) and shear angle of link slot c, for the
//! divergence message.
std::string describe_link(const Model::Data& model, const VoxelState& voxels, int axis, int c,
                          float sin_t, float cos_t);

//! Elastic energy stored in the links of one axis (J), for diagnostics and tests.
double link_elastic_energy(const Model::Data& model, const VoxelState& voxels, int axis,
                           float sin_t, float cos_t);

}  // namespace bhm::engine
