#pragma once
// What `bhm verify` leaves behind: the JSON report of one body or of a run's top K, the FEM's
// deformed mesh as legacy VTK (ParaView opens it beside the engine's VTK series), and the rank
// agreement of two scorings.
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "evo/verify/verify_body.hpp"

namespace bhm::evo {

nlohmann::json verification_to_json(const BodyVerification& v, const VerifyOptions& options);

//! Legacy VTK (ASCII unstructured grid) of the FEM mesh moved by `u`, with the displacement as
//! point vectors and the material as cell scalars.
std::string fem_mesh_vtk(const FemModel& model, const NodalDisplacements& u,
                         const std::string& title);

//! Spearman's rank correlation (ties share their mean rank); NaN for fewer than 2 values or a
//! constant list.
double spearman(const std::vector<double>& a, const std::vector<double>& b);

}  // namespace bhm::evo
