#pragma once
// The CalculiX input deck of a FemModel: nodes, elements, one material per palette entry used
// (E, nu, density, and the expansion coefficient of active materials), the held nodes, gravity,
// and one static step per load: the body at rest under gravity, then a uniform temperature
// change of +A and -A (only materials with a cte expand). Displacements of every node are printed
// at the end of each step.
//
// A muscle body (engine/muscle.hpp) has the loads rest and peak activation, its "temperature" the
// activation a (0, then 1): a muscle material's expansion is orthotropic (*EXPANSION, TYPE=ORTHO,
// in the global axes, which are the lattice's), -contraction_strain per unit a along its fibre
// and +nu contraction_strain across it, the free strain muscle::axis_strain of our engine. A
// muscle only contracts: there is no -A. Muscle voxels with their own fibre axis
// (BodySpec::fibre_axis) form one element set and material per (material, axis), "M3Y" / "MAT3Y".
#include <string>
#include <vector>

#include "engine/body_spec.hpp"
#include "evo/verify/fem_model.hpp"

namespace bhm::evo {

struct FemLoad {
    std::string name;            //!< "rest", "+A", "-A"; a muscle body's "rest", "peak"
    double temperature_c = 0.0;  //!< uniform temperature change of the step (a muscle body: a)
};

//! Whether the body's active voxels are muscle (a body never mixes them with sine-active ones,
//! muscle::palette_problems): its loads are then rest and peak activation.
bool muscle_driven(const engine::BodySpec& spec);

//! The material law of the nonlinear steps. A material in Table 1 is only E and nu, so its
//! large-strain law is unknown; these are the two standard hyperelastic laws with those small-
//! strain moduli, which `bhm verify` solves side by side (docs/verify.md, "Two continuum laws").
//! - Hooke: *ELASTIC, which under NLGEOM is Hooke's law on the Green-Lagrange strain (Saint
//!   Venant-Kirchhoff): it softens in compression.
//! - NeoHookean: *HYPERELASTIC, NEO HOOKE with C10 = G / 2 and D1 = 2 / K (ccx's compressible
//!   form, K = E / (3 (1 - 2 nu))): the usual law of soft tissue and gels.
//! Both take the thermal strain off the deformation gradient (ccx's calcmechstrain: F - eth I).
//! Linear steps are Hooke's either way.
enum class FemMaterialLaw { Hooke, NeoHookean };
//! "Saint Venant-Kirchhoff" or "Neo-Hookean" (the report's and the verdict's name).
const char* fem_material_law_name(FemMaterialLaw law);

//! ccx's Newton controls of the nonlinear steps (ignored for linear steps).
//! - CcxDefaults: ccx's own (*CONTROLS not written): an increment converges once the largest
//!   residual force is within 0.5 % of the average force and the largest correction within 1 %
//!   of the increment's displacement; an increment is enlarged by 1.5 after two in a row that
//!   converged in at most 4 iterations.
//! - Loose: the coarse mesh's nonlinear part (docs/verify.md, "loop40c"): an increment is doubled
//!   after two in a row that converged in at most 6 iterations; the convergence tolerances stay
//!   ccx's (loosening them moved one answer by 11 %). Measured on the loop's picks: 9-14 % fewer
//!   Newton iterations, the answers within 2e-3 of the largest displacement.
enum class FemNewtonControls { CcxDefaults, Loose };

//! The deck; `nlgeom` solves each step geometrically nonlinear (large rotations), in increments,
//! with `law`'s material and `newton`'s controls (both ignored for linear steps).
//! `full_integration` writes a C3D20R model's elements as C3D20 (the same 20 nodes and shape
//! functions, 27 integration points instead of 8): the coarse mesh of a body with a section 1
//! voxel across, and the coarse mesh's fallback where its reduced-integration nonlinear solve
//! fails (docs/verify.md, "loop40c", "loop40d"); its actuated nonlinear steps that would start
//! whole start at a quarter, where ccx went on after abandoning them whole.
std::string ccx_deck(const FemModel& model, const engine::BodySpec& spec,
                     const std::vector<FemLoad>& loads, bool nlgeom,
                     FemMaterialLaw law = FemMaterialLaw::Hooke,
                     FemNewtonControls newton = FemNewtonControls::CcxDefaults,
                     bool full_integration = false);

}  // namespace bhm::evo
