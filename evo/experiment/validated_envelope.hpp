#pragma once
// The envelope in which the engine's bodies are validated against the continuum (CalculiX and
// theory), as docs/physics.md states it ("Validation: ours vs CalculiX vs theory" and "Known
// limits"). The numbers live here and nowhere else; when docs/physics.md moves the envelope
// change them here and in its table together.
// Outside the envelope a body still runs (engine/limits.hpp decides what runs); `bhm validate`
// and the studio warn, they do not refuse.
#include <optional>
#include <string>
#include <vector>

#include "evo/experiment/experiment.hpp"
#include "evo/experiment/experiment_io.hpp"

namespace bhm::evo::validated {

//! Largest max E / min E trusted: layered and cored bodies within 2.3 % of CalculiX up to 10 for
//! 0 <= nu <= 0.49, the heated soft-on-stiff bilayer within 4.7 %, checkerboards (stiff voxels
//! meeting along edges) within 4.0 % of the continuum (docs/physics.md, "Bodies of several
//! materials"). At 100 layered and cored bodies are within 4.8 %, but a checkerboard's continuum
//! value beyond 30 is not known to 5 %, and evolution makes such mixtures, so the envelope stays
//! at 10. Inside this contrast any nu of the range below is trusted.
inline constexpr double kMaxStiffnessContrast = 10.0;
//! Poisson's ratios validated in bending and axial tests: 0, 0.2, 0.35, 0.49. Auxetic voxels
//! (nu < 0) pass axial tests only ("Known limits": not tested in bending).
inline constexpr double kMinPoissonRatio = 0.0;
inline constexpr double kMaxPoissonRatio = 0.49;
//! Largest muscle contraction strain that runs whatever the twitch's rise time (the muscle
//! envelope fuzz, docs/physics.md "Known limits"): a rise faster than an elastic wave's transit of
//! the body acts as a step of rest length, the body overshoots to about 1 - 2 e of its length,
//! and past e = 0.45 a link can be squeezed below the engine's 0.1 L guard.
inline constexpr double kFastTwitchMaxStrain = 0.45;

}  // namespace bhm::evo::validated

namespace bhm::evo {

//! Warnings (not errors) for an experiment whose materials lie outside the validated envelope:
//! the stiffness contrast and Poisson's ratios of the materials the body uses (with the frame and
//! overrides), or of every material of the experiment when there is no body; and a muscle whose
//! twitch rises faster than a wave crosses the workspace at a strain past kFastTwitchMaxStrain
//! (its body may stop as diverged). Each is a Problem
//! whose message starts with "warning: ".
std::vector<Problem> envelope_warnings(const Experiment& experiment, const Body* body,
                                       const std::string& file_label);

}  // namespace bhm::evo
