#pragma once
// Private to the engine: how much stiffer a link is where one of its ends sits in a wider region
// than the link itself (issue 40: a body held by a few voxels, a neck inside a body).
//
// A link is a beam from voxel centre to voxel centre, each half inside its own voxel. Where both
// ends are alike (a uniform body, a one-voxel-thick column) the half-links are what the continuum
// has. Where a narrow part (a held patch of one to a few voxels, a neck) meets a wide layer, the
// half-link inside the wide layer's voxel is not a free 1 x 1 bar: that voxel is bonded to lateral
// neighbours that have no link on the same side, and the stress of the narrow part spreads into
// them within the voxel. The engine made the whole link a narrow bar, so every narrow part was
// about a voxel too long: bodies held by 1-8 voxels sagged 13-51 % more than CalculiX at nu 0.35
// and necks 25-56 % (docs/physics.md, "Narrow attachments and necks").
//
// Each half-link is a spring in series with the other; a confined half is stiffer by
//   kappa = 1 + c n g(nu),
// n the count of its voxel's lateral neighbours (0..4) without a link on that side, g a function
// of the P-wave modulus over E, M / E = (1 - nu) / ((1 + nu) (1 - 2 nu)): sqrt(M / E) for bending,
// torsion and shear (the spreading is a laterally constrained strain, stiffer with nu as a bonded
// layer is), 1 for the axial mode (its normal stress already carries the Poisson coupling's
// volumetric term). The link's stiffness in each mode becomes
// 2 / (1 / kappa_a + 1 / kappa_b) of the plain link's (kappa = 1 at an end that is not confined),
// capped at twice it so that the stable step, which knows only the plain link, still bounds it.
// c = 1/3, the two exponents (1/2 and 0) and the penalty on the split of links of one material
// (poisson.cpp, kSameMaterialSplitPenalty) are fitted together on the fitting half of the
// continuum suite (tests/engine/test_engine_continuum.cpp), which also lists the held-out half
// they are judged on. (With the equal split, which locked 2-voxel-tall sections at nu 0.49, the
// axial exponent was -1/2; docs/physics.md, "The relaxed split on every link".)
//
// Necks (issue 40; docs/physics.md, "Necks: the lateral stress of a confined end"). Where neither
// end of the link is held and no held voxel confines the half-link (a neck or a step inside the
// free body, not a held patch, whose clamp has its own lateral constraint in poisson.cpp), the
// confined half's stiffening follows the neck's lateral restraint. A short neck bonded to wide
// blocks cannot contract freely at its ends: there the block holds it in uniaxial strain, whose
// lateral stress is K0 = nu / (1 - nu) times the axial one (lambda / (lambda + 2 G)), and the
// restraint reaches further into a neck the wider it is against its length (a bonded layer's shape
// factor S = loaded area / free area; one voxel long, S = 1 / (free lateral faces of the narrow
// voxel): 1/4 for a 1x1 neck, 1/3 for 1x2, 1/2 for 2x2). So the bending and torsion g is
//   g = 1 + a S K0,
// which rises steeply from nu 0 and stays bounded as nu -> 1/2 (the continuum's necks stiffen by
// 5 % from nu 0 to 0.35 and 6 % more to 0.49, where sqrt(M / E) went 1 -> 1.27 -> 4.1), with c_neck
// for c; the axial g is E / M: the normal stress of the confined half already carries the wide
// voxel's laterally coupled octants (up to M), which the spread would otherwise count twice (it
// locked 2-voxel-tall necks at nu 0.49). An auxetic end (nu < 0) takes K0 = 0 (not measured; a
// negative K0 made kappa negative and 16 of the muscle envelope fuzz's 80 bodies diverge). c_neck,
// a and the axial exponent were swept on the fitting necks (neck1, neck2x2) only; neck1x2 and
// neck2x1 are held out.
#include "engine/internal/model_data.hpp"

namespace bhm::engine {

inline constexpr double kConfinedHalfStiffening = 1.0 / 3.0;  //!< c above
inline constexpr double kConfinedLinkCap = 2.0;               //!< at most this times the plain link
inline constexpr double kNeckHalfStiffening = 1.4 / 3.0;      //!< c_neck above (bending, torsion)
inline constexpr double kNeckLateralStress = 7.0;             //!< a above

//! Lateral neighbours of voxel `v` (across `axis`) that have no link on `side` (+1 or -1) along
//! `axis`: the material beside the half-link that the half-link's stress spreads into.
int confining_neighbours(const Model::Data& d, int v, int axis, int side);

//! Whether any of those confining neighbours is held (the half-link sits at the clamp).
bool held_confining_neighbour(const Model::Data& d, int v, int axis, int side);

struct ConfinedLinkFactors {
    double axial = 1.0;    //!< on the axial stiffness (and the link's normal stress)
    double bending = 1.0;  //!< on the bending and torsion stiffness (and so the shear)
};

//! The factors on the stiffness of the link from `v` (- end) to `b` (+ end) along `axis`, with
//! Poisson's ratios nu_v and nu_b of the two ends: 1 for a link without a confined end.
ConfinedLinkFactors confined_link_factors(const Model::Data& d, int v, int b, int axis, double nu_v,
                                          double nu_b);

// A link joining two materials (issue 40: random mixtures). Both halves carry the link's normal
// stress, and each contracts across it by nu sigma / E, the soft half `contrast` times more than
// the stiff half it is bonded to. In the continuum the stiff face restrains the contraction of a
// soft layer, so the soft material near the interface is stiffer along the link, toward its P-wave
// modulus M (a bonded layer); the lattice let the halves contract apart, and soft layers between
// stiff ones came out 8-42 % too soft at nu 0.35-0.49 (slices of 3-30x, 12x4x4), random 50/50 and
// 30/70 mixtures up to 25 %, while nu = 0 was right (docs/physics.md, "Mixtures"). A bonded layer
// confines only as far as it extends sideways (a rubber pad's shape factor): a soft voxel whose
// neighbours across the link are stiff (a checkerboard) is not a layer, and stiffening it put the
// 10x checkerboard 14 % stiff at nu 0.49. So the soft half is stiffer by
//   kappa = 1 + c (n / 4) (1 - 1 / contrast)^p (1 - E / M)^q,
// n the soft voxel's lateral neighbours (0..4) of its own material. kappa is 1 for one material
// and at nu = 0 (M = E), and below M / E (the fully bonded layer) for every nu, since
// 1 + c x^q <= 1 + x <= 1 / (1 - x) with x = 1 - E / M and c <= 1. c, p and q are fitted on the
// slices alone (the fitting half, tests/engine/test_engine_calculix_mixed.cpp); the random
// mixtures and the layered, cored, heated and checkerboard bodies are the held-out half.
inline constexpr double kMixedSoftStiffening = 0.9;    //!< c above
inline constexpr double kMixedContrastExponent = 2.0;  //!< p above
inline constexpr double kMixedPoissonExponent = 1.5;   //!< q above

//! Lateral neighbours of voxel `v` (across `axis`) of v's own material, 0..4.
int same_material_lateral_neighbours(const Model::Data& d, int v, int axis);

//! The factor on the axial stiffness of the link from `v` (material mv) to `b` (mb) along `axis`:
//! (contrast + 1) / (contrast / kappa + 1), 1 where the two ends' Young's moduli are equal.
double mixed_link_stiffening(const Model::Data& d, int v, int b, int axis, const Material& mv,
                             const Material& mb);

// The bending and torsion (and so shear) modes of a link joining two materials (issue 40: random
// mixtures at nu = 0). They stand for the two half-voxels' own curvature and shear, taken in series
// (the harmonic mean), which is exact where the moment and the shear force are continuous along the
// link: a laminate (slices, layers, a cored or heated strip) and a checkerboard's chains, where
// every link beside this one is mixed as it is. Where the links beside it are of material at least
// as stiff as its stiffer end (a soft voxel in the re-entrant corner of stiff material, common in
// random mixtures and absent from laminates and checkerboards), those stiff neighbours impose the
// section's curvature and shear on both halves, whose energies then add at their own moduli (the
// arithmetic mean, as Voigt's bound). Per such neighbour a quarter of the way:
//   factor = 1 + (s / 4) ((E_a + E_b)^2 / (4 E_a E_b) - 1),
// s the count (0..4) of the link's four lateral parallel links whose both ends are at least as
// stiff as its stiffer end. Nothing is fitted: laminates and checkerboards (the edge springs' and
// mixed_link_stiffening's fitting half) have s = 0 and are unchanged bit for bit; the random
// mixtures are judged on it (tests/engine/test_engine_calculix_mixed.cpp, docs/physics.md "Random
// mixtures"). At nu = 0 the 10x random 50/50 mix went from +5.4 % to +3.4 %.

//! Lateral parallel links of the link from `v` to `b` along `axis` whose both ends are at least as
//! stiff as the stiffer of v and b (0..4); 0 when v and b are of one Young's modulus.
int stiff_lateral_links(const Model::Data& d, int v, int b, int axis);

//! The factor on the bending and torsion stiffness of the link from `v` (material mv) to `b` (mb)
//! along `axis`: 1 where the two ends' Young's moduli are equal or no lateral link is stiffer.
double mixed_link_bending_factor(const Model::Data& d, int v, int b, int axis, const Material& mv,
                                 const Material& mb);

}  // namespace bhm::engine
