#pragma once
// What `bhm verify` leaves behind: the JSON report of one body or of a run's top K, both deformed
// shapes as voxel poses (shapes.json: what the studio draws), the FEM's deformed mesh as legacy
// VTK (ParaView opens it beside the engine's VTK series), and the rank agreement of two scorings.
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "engine/poses.hpp"
#include "evo/verify/verify_body.hpp"

namespace bhm::evo {

nlohmann::json verification_to_json(const BodyVerification& v, const VerifyOptions& options);

//! Legacy VTK (ASCII unstructured grid) of the FEM mesh moved by `u`, with the displacement as
//! point vectors and the material as cell scalars.
std::string fem_mesh_vtk(const FemModel& model, const NodalDisplacements& u,
                         const std::string& title);

//! Both answers' deformed voxels at every load (LoadComparison::fem_shape, engine_shape).
nlohmann::json verification_shapes_json(const BodyVerification& v);

struct VerificationShapes {
    std::vector<int> voxel_cells;  //!< lattice cell of each voxel, the poses' order
    std::vector<std::string> loads;
    std::vector<engine::VoxelPoses> fem, engine;  //!< per load
};
//! Reads verification_shapes_json's output; throws std::runtime_error naming `file` and the
//! field when it is malformed.
VerificationShapes verification_shapes_from_json(const nlohmann::json& j, const std::string& file);

//! Writes report.json, shapes.json and the FEM's mesh per load (fem-rest.vtk, fem-plus-A.vtk,
//! fem-minus-A.vtk; a muscle body fem-rest.vtk, fem-peak.vtk) into `dir` (created), each file
//! atomically; returns the report.
nlohmann::json write_verification(const BodyVerification& v, const VerifyOptions& options,
                                  const std::string& dir);

//! Whether `name` is a file write_verification writes (report.json, shapes.json, fem-*.vtk): the
//! entries a folder replaced whole by a new verification may hold (engine/io/staged_folder.hpp).
bool is_verification_file(const std::string& name);

//! Spearman's rank correlation (ties share their mean rank); NaN for fewer than 2 values or a
//! constant list.
double spearman(const std::vector<double>& a, const std::vector<double>& b);

}  // namespace bhm::evo
