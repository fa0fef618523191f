#pragma once
// The verification's automatic mesh (issue 40): refined where the body is narrow. A structured
// C3D8I mesh with 2 elements per voxel edge is within 0.3 % of a mesh 8x finer on wide bodies,
// but 20-25 % too stiff where load passes through one voxel (a body held by a single voxel, a
// 1x1 neck): there the re-entrant corners and the small clamp need quadratic elements and more of
// them across. So the body's narrowest section is measured: one 1 voxel across gets C3D20R with
// 2 elements per voxel edge (within 5 % of C3D20R with 4 there, at a twentieth of its solve),
// unless that passes the cost cap or a held voxel is clamped at a point (where no refinement
// converges); a body whose sections are all at least 2 voxels across keeps C3D8I with 2.
// docs/verify.md, "The automatic mesh", has the measured figures.
#include <array>
#include <string>

#include "engine/body_spec.hpp"
#include "evo/verify/fem_model.hpp"

namespace bhm::evo {

//! The body's narrowest section, in whole voxels. For each free voxel the load path is taken
//! along the axis of its largest offset from the root (the held voxels' centroid), and the
//! section across it is the smaller of the two contiguous material runs through the voxel on the
//! other two axes; for the held voxels, the clamp's width is the second-smallest contiguous run
//! of held voxels through one (a held face layer is thin along its normal, not across it). The
//! narrowest is the smallest of all: 1 for a body held by a single voxel, a 1x1 or 1x2 neck, or a
//! part one voxel thick.
struct NarrowestSection {
    int width_voxels = 0;     //!< 0 when the body has no material voxel
    std::array<int, 3> at{};  //!< a voxel where it is (the first in lattice order)
    bool held = false;        //!< the clamp (held voxels), not a free part
};
NarrowestSection narrowest_section(const engine::BodySpec& spec);

//! A section this many voxels across or fewer is refined.
inline constexpr int kNarrowSectionVoxels = 1;
//! The largest refined mesh the automatic choice picks, in estimated nodes (fem_mesh_cost): about
//! a minute of ccx CPU for a linear C3D20R solve on this machine class (docs/verify.md, "The
//! automatic mesh"); C3D20R at 2 per edge up to 1250 voxels.
inline constexpr double kMeshCostCapNodes = 40000.0;

//! The estimated node count of `voxels` voxels meshed as `mesh`: s^3 elements per voxel, about 4
//! nodes per C3D20R element and 1 per C3D8I element on a structured grid (a body's surface adds
//! some: the 10x3x3 bodies of docs/verify.md have 1.4-1.6 times this).
double fem_mesh_cost(int voxels, const FemMeshOptions& mesh);

struct FemMeshChoice {
    FemMeshOptions mesh;
    bool automatic = true;
    NarrowestSection narrowest;  //!< automatic only
    bool capped = false;         //!< refinement was wanted but passed kMeshCostCapNodes
    //! A held voxel is clamped at a point or along a line (held inside the body): a singular
    //! support whose sag grows with refinement (2.06 mm at C3D8I 2, 3.06 mm at C3D20R 2 on the
    //! 12x3x3 bar of docs/verify.md), so C3D8I with 2 stays.
    bool point_clamp = false;
    //! "C3D20R, 2 per voxel edge: narrowest section 1 voxel across (the held patch at voxel
    //! (0, 1, 1))", "C3D8I, 2 per voxel edge: every section at least 3 voxels across", or
    //! "C3D20R, 4 per voxel edge: chosen by the caller (--element, --subdivision)".
    std::string reason;
};

//! "C3D20R, 2 per voxel edge".
std::string describe_fem_mesh(const FemMeshOptions& mesh);

//! The automatic mesh of `spec` (docs/verify.md, "The automatic mesh").
FemMeshChoice choose_fem_mesh(const engine::BodySpec& spec);

//! A mesh the caller chose; its reason says so.
FemMeshChoice explicit_fem_mesh(const FemMeshOptions& mesh);

}  // namespace bhm::evo
