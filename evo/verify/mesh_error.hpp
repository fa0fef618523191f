#pragma once
// The FEM's own discretisation error, estimated from a second mesh: the body solved again at
// another subdivision (twice it up to 4, else half; same element, same linear or nonlinear
// steps) and the deciding measure compared between the two meshes (docs/verify.md, "The FEM's
// mesh error"). Printed beside the verdict, so that a difference between the models can be read
// against how far the continuum's own answer still moves with its mesh.
#include <optional>

#include "engine/body_spec.hpp"
#include "evo/experiment/experiment.hpp"
#include "evo/verify/verify_body.hpp"

namespace bhm::evo {

struct MeshErrorEstimate {
    int subdivision = 0;    //!< the second mesh's elements per voxel edge
    double relative = 0.0;  //!< |second - first| / |first| of the deciding measure (largest load)
    double fem_cpu_s = 0.0;  //!< the second solve's ccx CPU time
};

//! Subdivision 1 goes to 2, 2 to 4, 3 to 1 and 4 to 2. nullopt where `v` was not compared or
//! nothing decided its verdict. Throws as verify_body does.
std::optional<MeshErrorEstimate> estimate_mesh_error(const engine::BodySpec& spec,
                                                     FitnessMeasure fitness,
                                                     const BodyVerification& v,
                                                     const VerifyOptions& options);

}  // namespace bhm::evo
