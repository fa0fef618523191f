#pragma once
// The CalculiX input deck of a FemModel: nodes, elements, one material per palette entry used
// (E, nu, density, and the expansion coefficient of active materials), the held nodes, gravity,
// and one static step per load: the body at rest under gravity, then a uniform temperature
// change of +A and -A (only materials with a cte expand). Displacements of every node are printed
// at the end of each step.
#include <string>
#include <vector>

#include "engine/body_spec.hpp"
#include "evo/verify/fem_model.hpp"

namespace bhm::evo {

struct FemLoad {
    std::string name;             //!< "rest", "+A", "-A"
    double temperature_c = 0.0;   //!< uniform temperature change of the step
};

//! The deck; `nlgeom` solves each step geometrically nonlinear (large rotations), in increments.
std::string ccx_deck(const FemModel& model, const engine::BodySpec& spec,
                     const std::vector<FemLoad>& loads, bool nlgeom);

}  // namespace bhm::evo
