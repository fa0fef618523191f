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
// layer is), 1 / sqrt(M / E) for the axial mode (its normal stress already carries the Poisson
// coupling's volumetric term, which grows with nu: with sqrt(M / E) there too, 2 x 2 stalks came
// out 13-15 % stiff at nu 0.49). The link's stiffness in each mode becomes
// 2 / (1 / kappa_a + 1 / kappa_b) of the plain link's (kappa = 1 at an end that is not confined),
// capped at twice it so that the stable step, which knows only the plain link, still bounds it.
// c = 1/3 and the two exponents are fitted on the fitting half of the continuum suite
// (tests/engine/test_engine_continuum.cpp), which also lists the held-out half they are judged on.
#include "engine/internal/model_data.hpp"

namespace bhm::engine {

inline constexpr double kConfinedHalfStiffening = 1.0 / 3.0;  //!< c above
inline constexpr double kConfinedLinkCap = 2.0;               //!< at most this times the plain link

//! Lateral neighbours of voxel `v` (across `axis`) that have no link on `side` (+1 or -1) along
//! `axis`: the material beside the half-link that the half-link's stress spreads into.
int confining_neighbours(const Model::Data& d, int v, int axis, int side);

struct ConfinedLinkFactors {
    double axial = 1.0;    //!< on the axial stiffness (and the link's normal stress)
    double bending = 1.0;  //!< on the bending and torsion stiffness (and so the shear)
};

//! The factors on the stiffness of the link from `v` (- end) to `b` (+ end) along `axis`, with
//! Poisson's ratios nu_v and nu_b of the two ends: 1 for a link without a confined end.
ConfinedLinkFactors confined_link_factors(const Model::Data& d, int v, int b, int axis, double nu_v,
                                          double nu_b);

}  // namespace bhm::engine
