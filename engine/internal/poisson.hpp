#pragma once
// Private to the engine: Poisson's ratio as 3-D Hooke's law for the normal strains.
//
// Each voxel is split into eight octants, one per choice of its - or + half-link on each axis.
// An octant's normal-strain energy is isotropic Hooke's law written as
//   W_o = V / 8 (G sum_a gamma_a^2 + lambda_k / 2 theta^2),  theta = sum_a mu_a,
// over the k axes whose half-link exists on its side (a missing half-link is a free surface: the
// moduli are condensed, lambda_3 = lambda = E nu / ((1 + nu)(1 - 2 nu)), lambda_2 = E nu /
// (1 - nu^2) (plane stress), lambda_1 = E nu / (1 + nu) (uniaxial), G = E / (2 (1 + nu))).
// gamma is the half-link's own strain (the deviatoric term, which also holds the lattice's
// checkerboard modes), and mu is the strain at the voxel's centre, the same for all octants (the
// volumetric term, B-bar style): the mean of the two half-links inside a column; the derivative of
// the parabola through the last three centres, (3 e_link - e_next) / 2, at the end of a column of
// three or more (unless its partner or far link is stiffer than the end voxel, which then keeps its
// half-link: poisson.cpp); and e_link -+ d at the two ends of an isolated link (a column of two), d
// a relaxed internal variable (a per-link state, one under-relaxed Jacobi step per step: each step
// only lowers the energy, so it damps and never pumps). Sampling the volumetric strain at the
// centres is what removes the locking: in bending the lateral strain nu kappa z varies through a
// layer, the half-links of a column see it half a voxel off the axial strain of the voxel's centre,
// and near nu = 0.5 every such mismatch cost the bulk modulus (the earlier per-half-link form was
// 17 % too stiff at nu = 0.49). A uniform strain is exact for any section (so a free bar contracts
// by -nu eps and keeps E), the energy is positive for nu >= 0 (auxetic voxels keep half-link
// strains), and at nu = 0 it is the links' own E e^2 / 2.
//
// A link between two materials (E, nu or the free strain of actuation differ, both ends coupled)
// splits its strain between its halves as h = w e -+ d: w the series weights (stress continuity
// along the link, 2 E_p / (E_v + E_p), right for a bar in tension) and d the same kind of relaxed
// internal variable as an isolated link's, so the split settles where the full normal stress of
// both halves, lateral Poisson terms included, is continuous (the minimum of the octants' energy
// over d). The lateral strains of bending, equal in both materials, are no longer forced into the
// softer half. The reduced energy min_d W is never stiffer than W at d = 0, so the stable step and
// the damping cap still hold; d enters a column's centre strain with the half-link's weight in the
// mean (1/2 inside a column, 3/2 in an end's extrapolation).
//
// A link of one material (both ends coupled, inside a column) takes such a d too, held by a
// penalty x E d^2 / 2 per volume (x = 10, poisson.cpp): with the equal split (x = infinity) a
// section two voxels tall locked near nu = 0.5 (in bending its voxels' lateral strains alternate,
// which the mean of two half-links cannot), and such stalks and necks were 14-19 % too stiff at
// nu 0.49; a free split (x = 0) lets every link's halves part and a uniform block went too soft.
// Every body with nu > 0 therefore runs the mixed kernels (docs/physics.md, "The relaxed split on
// every link").
//
// A held voxel is the clamp plane through its centre; its octants are uncoupled (nu = 0) except
// inside a held face of its own material, where an octant with both lateral half-links takes
// lambda_2 (poisson.cpp, kHeldFaceConstraint): the clamp holds the material laterally, which a
// uniform cantilever feels as a stiffer root near nu = 0.5 (docs/physics.md, "The clamp's lateral
// constraint").
//
// At large strains (an active region held by a passive frame or the clamp, contracted to
// 0.4 L while its lateral links are held near L) the linear volumetric stress would push a link
// past zero length; it saturates instead, lambda theta / sqrt(1 + (theta / theta_0)^2) with
// theta_0 = 0.2 (energy lambda theta_0^2 (sqrt(1 + (theta / theta_0)^2) - 1), still convex;
// 0.5 % below linear at a volume strain of 0.02, 11 % at 0.1).
//
// The coupling is applied as a shift of each link's rest length, computed from the current
// positions before the link passes (no lag: a lagged coupling feeds energy into the volumetric
// modes): shift = L e - L sigma / M_link with sigma = dW/de / V, so the link kernel, with its
// own stiffness M_link L, exerts exactly dW/de.
#include "engine/internal/model_data.hpp"
#include "engine/internal/world_state.hpp"

namespace bhm::engine {

struct PoissonModuli {
    double m = 0.0;       //!< modulus of a link's own strain (M, plane-stress or E)
    double lambda = 0.0;  //!< modulus of the cross strains
};

//! lambda_k = M_k - 2 G of an octant with k linked axes (0 for none).
double octant_volumetric_modulus(double youngs_modulus, double nu, int linked_axes);

//! Fills Model::Data::poisson (except the link slots' rest_scale) and returns, per axis and
//! voxel, the mean over its octants of the link-axis modulus M_k / E (a link's own modulus).
std::array<std::vector<double>, 3> build_poisson_params(Model::Data& model);
//! After the links are built: the relaxation steps of the d of isolated and mixed links.
void finish_poisson_params(Model::Data& model);

//! Moduli of a voxel of Young's modulus E and Poisson's ratio nu with `linked_axes` (1..3) axes
//! carrying links.
PoissonModuli poisson_moduli(double youngs_modulus, double nu, int linked_axes);

//! Largest stiffness of a voxel's normal modes relative to E (the uniaxial-strain M or the
//! volumetric 3K = E / (1 - 2 nu), whichever is larger; 1 at nu = 0): bounds the modes the
//! explicit bond damping acts on (Model::build's damping cap).
double poisson_stiffness_factor(double nu);
//! The P-wave modulus M = lambda + 2 G over E, at least 1: the stiffest wave of the continuum,
//! which scales the stable step.
double poisson_wave_factor(double nu);

//! Sizes the Poisson scratch of a World (once, so a step allocates nothing).
void prepare_poisson_scratch(const Model::Data& model, PoissonScratch& scratch);

//! From the current positions: every link's strain, chord and length, and the normal stresses
//! (in `scratch` and `links`) from which the link pass forms the rest-length shifts; then relaxes
//! the d of isolated and mixed links (the one state in `scratch`).
void poisson_pass(const Model::Data& model, const VoxelState& voxels,
                  std::array<LinkScratch, 3>& links, PoissonScratch& scratch, float sin_t,
                  float cos_t);

//! The octants' energy less the links' own M_link V e^2 / 2 (J), at the current positions and d
//! (`state`); link_elastic_energy holds the rest.
double poisson_cross_energy(const Model::Data& model, const VoxelState& voxels,
                            const PoissonScratch& state, float sin_t, float cos_t);

}  // namespace bhm::engine
