#pragma once
// The FEM's own discretisation error, estimated from a second mesh: the body's FEM solved again
// at another subdivision (twice it up to 4, else half; same element, same linear or nonlinear
// steps) and the deciding measure compared between the two meshes (docs/verify.md, "The FEM's
// mesh error"). Printed beside the verdict, so that a difference between the models can be read
// against how far the continuum's own answer still moves with its mesh. Only the FEM is solved
// again: our engine's answer does not depend on the FEM's mesh.
#include <optional>
#include <string>

#include <nlohmann/json.hpp>

#include "engine/body_spec.hpp"
#include "evo/verify/verify_body.hpp"

namespace bhm::evo {

//! The second mesh is not solved above this many estimated nodes (fem_mesh_cost): twice the
//! automatic choice's cap, a few minutes of ccx at most (docs/verify.md).
inline constexpr double kMeshErrorCapNodes = 2.0 * kMeshCostCapNodes;

struct MeshErrorEstimate {
    int subdivision = 0;        //!< the second mesh's elements per voxel edge
    int first_subdivision = 0;  //!< the verification's
    double relative = 0.0;      //!< |second - first| / |first|, deciding measure, largest load
    double fem_cpu_s = 0.0;     //!< the second solve's ccx CPU time
    //! Non-empty when the second mesh was not solved: "4 per edge would be about 114688 nodes,
    //! over the 80000 cap" (relative is then 0).
    std::string skipped;
};

//! Subdivision 1 goes to 2, 2 to 4, 3 to 1 and 4 to 2.
int second_subdivision(int subdivision);

//! nullopt where `v` was not compared or nothing decided its verdict. Throws as verify_body does
//! (VerifyCancelled when options.control's flag is raised).
std::optional<MeshErrorEstimate> estimate_mesh_error(const engine::BodySpec& spec,
                                                     const BodyVerification& v,
                                                     const VerifyOptions& options);

//! "FEM mesh error ~5.2 % (2 vs 4 per edge)", or "FEM mesh error not estimated: ...".
std::string describe_mesh_error(const MeshErrorEstimate& e);

//! report.json's `fem_mesh_error` (the CLI and the studio write the same): the deciding measure,
//! both subdivisions, the relative difference and the second solve's CPU time, or `skipped`.
nlohmann::json mesh_error_json(const MeshErrorEstimate& e, const BodyVerification& v);

}  // namespace bhm::evo
