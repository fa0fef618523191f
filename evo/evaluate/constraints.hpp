#pragma once
// Validity of a phenotype under the experiment's constraints (paper section 4.1: "otherwise the
// morphology design is considered invalid"). An invalid phenotype is never simulated.
//  - always: the CPPN must fill at least one cell of the design space;
//  - attached_to_fixed_face: for every face marked fixed, the design-space layer nearest that face
//    holds a filled cell (without a frame that layer is the workspace face itself; with a frame it
//    is the layer touching the frame next to the fixed face). No fixed face: nothing to check;
//  - min_fill_fraction: filled design-space cells / design-space cells;
//  - min_active_voxels: active cells of the whole framed phenotype;
//  - reject_escaped: every voxel of the framed phenotype is held or face-connected to a held one
//    (the escaped flag of evo/evaluate/exploit_flags.hpp, known without simulating).
#include <string>

#include "evo/experiment/experiment.hpp"
#include "evo/genome/phenotype.hpp"

namespace bhm::evo {

//! Empty when valid, else a short reason ("not attached to the fixed x- face").
std::string constraint_violation(const Constraints& constraints, const Boundary& boundary,
                                 const DesignSpace& space, const Phenotype& phenotype);

bool touches_design_layer(const Phenotype& phenotype, const DesignSpace& space, Face face);

}  // namespace bhm::evo
