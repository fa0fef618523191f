#pragma once
// A body's continuum model for CalculiX: every voxel split into s x s x s hexahedra (C3D20R, the
// 20-node quadratic brick with reduced integration, or C3D8I, the 8-node brick with incompatible
// modes) on one structured grid, so face-joined voxels share their nodes (voxels touching only
// along an edge or at a corner do not: our engine does not bond them); each element carries
// its voxel's material. Held voxels are clamped where the engine holds them, at their centre: a
// node of a held voxel is fixed when it is at least half a voxel (L-infinity) from every free
// voxel, which for a fixed face layer is the plane through the layer's centres, and a held voxel
// whose fixed nodes leave it free to turn has its rotation held by ties (docs/verify.md).
#include <array>
#include <string>
#include <vector>

#include "engine/body_spec.hpp"

namespace bhm::evo {

enum class FemElement { C3D20R, C3D8I };

struct FemMeshOptions {
    FemElement element = FemElement::C3D8I;
    int subdivision = 2;  //!< elements per voxel edge (an even count puts a node at each centre)
};

//! A linear constraint u_dof(dependent) = u_dof(independent) (ccx *EQUATION; dof 1..3).
struct FemTie {
    int dependent = 0, independent = 0, dof = 1;
};

struct FemModel {
    FemMeshOptions options;
    double voxel_size_m = 0.01;
    int points_per_voxel = 4;          //!< grid points per voxel edge (s, or 2 s for C3D20R)
    std::array<int, 3> grid{};         //!< grid points per axis
    std::vector<std::array<int, 3>> node_grid;  //!< node id - 1 -> grid point
    std::vector<std::vector<int>> elements;     //!< node ids in Abaqus order (8 or 20)
    std::vector<int> element_material;          //!< 1-based material index of each element
    //! Each element's own fibre axis (0 x, 1 y, 2 z) where its voxel is muscle and has one
    //! other than its material's (BodySpec::fibre_axis); -1: its material's (ccx_deck.hpp)
    std::vector<int> element_fibre;
    std::vector<int> fixed_nodes;  //!< node ids held in all three directions
    //! A held voxel's rotation where its fixed nodes do not hold it (one inside the body, whose
    //! neighbours are all free, has only its centre fixed): for each axis whose two face-centre
    //! nodes are both free, their displacements across that axis are tied equal, so the line
    //! through the fixed centre cannot turn (docs/verify.md).
    std::vector<FemTie> rotation_ties;
    std::vector<int> voxel_cells;               //!< the body's material cells, in lattice order
    //! Per voxel: node ids and weights whose sum is the displacement of the voxel's centre.
    std::vector<std::vector<std::pair<int, double>>> voxel_centre;
    //! Per voxel: the node ids of its 8 corners, corner (i, j, k) at index i + 2 j + 4 k.
    std::vector<std::array<int, 8>> voxel_corners;

    std::array<double, 3> node_position_m(int id) const;
    int node_count() const { return static_cast<int>(node_grid.size()); }
};

//! Meshes the material cells of `spec`. Throws std::invalid_argument on a bad subdivision.
FemModel build_fem_model(const engine::BodySpec& spec, const FemMeshOptions& options);

std::string fem_element_name(FemElement element);
//! "C3D20R" or "C3D8I"; throws std::invalid_argument naming the accepted names.
FemElement parse_fem_element(const std::string& name);

}  // namespace bhm::evo
