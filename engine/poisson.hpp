#pragma once
// Private to the engine: Poisson's ratio as 3-D Hooke's law for the normal strains.
//
// Each link carries the normal stress of isotropic linear elasticity along its axis a,
//   sigma_a = M e_a + lambda (e_b + e_c),  M = E (1 - nu) / ((1 + nu)(1 - 2 nu)),
//   lambda = E nu / ((1 + nu)(1 - 2 nu)),
// where e_a is the link's own mechanical strain (length minus its actuated rest length, over L)
// and e_b, e_c are the strains of the two end voxels along the other axes (the mean of each
// voxel's links on that axis), averaged over the two ends. A voxel with no link on an axis has a
// free surface there (zero normal stress), so its moduli are condensed: plane stress
// (M = E / (1 - nu^2), lambda = E nu / (1 - nu^2)) with two linked axes, plain E with one. So a
// free bar under axial strain eps contracts by -nu eps and keeps its Young's modulus, a laterally
// held one is stiffer (M), and a volume change meets the bulk modulus E / (3 (1 - 2 nu)). Bending
// stays the beam's E I (the cross terms only let the section deform), unlike a volumetric mode
// that stiffens every link by M / E (which locks near nu = 0.5).
//
// The coupling is applied as a shift of each link's rest length, computed from the current
// positions before the link passes (no lag: a lagged coupling feeds energy into the volumetric
// modes), so the link kernel only adds one term to its rest length.
#include "engine/model_data.hpp"
#include "engine/world_state.hpp"

namespace bhm::engine {

struct PoissonModuli {
    double m = 0.0;       //!< modulus of a link's own strain (M, plane-stress or E)
    double lambda = 0.0;  //!< modulus of the cross strains
};

//! Moduli of a voxel of Young's modulus E and Poisson's ratio nu with `linked_axes` (1..3) axes
//! carrying links.
PoissonModuli poisson_moduli(double youngs_modulus, double nu, int linked_axes);

//! Largest stiffness of a voxel's normal modes relative to E (the uniaxial-strain M or the
//! volumetric 3K = E / (1 - 2 nu), whichever is larger; 1 at nu = 0): scales the stable step.
double poisson_stiffness_factor(double nu);

//! Fills pp.cross_weight (sized `stored`) from has_plus / has_minus / lambda2 / lambda3: the
//! octant moduli depend only on which half-links exist, so each voxel's cross term is a fixed
//! linear combination of its lateral half-link strains (poisson.cpp).
void poisson_cross_weights(PoissonParams& pp, int stored);

//! Sizes the Poisson scratch of a World (once, so a step allocates nothing).
void prepare_poisson_scratch(const Model::Data& model, PoissonScratch& scratch);

//! Writes every link's rest-length shift (LinkScratch::poisson_rest) from the current positions:
//! shift = -L (lambda_a S_a + lambda_b S_b) / (2 M_link), S the end voxel's cross strains.
void poisson_pass(const Model::Data& model, const VoxelState& voxels,
                  std::array<LinkScratch, 3>& links, PoissonScratch& scratch, float sin_t,
                  float cos_t);

//! The cross-term energy sum_v V lambda_v (e_x e_y + e_y e_z + e_z e_x) of the current positions
//! (J), for diagnostics; the links' own M e^2 / 2 terms are in link_elastic_energy.
double poisson_cross_energy(const Model::Data& model, const VoxelState& voxels, float sin_t,
                            float cos_t);

}  // namespace bhm::engine
