#pragma once
// The outer surface of a voxel body as a closed, consistently oriented triangle mesh, for the
// next module of the pipeline (FEM, moulds, 3-D printing).
//
// Topology comes from the lattice: every face of an occupied cell whose neighbour is empty (or
// outside the lattice) becomes two triangles, wound counter-clockwise seen from outside, so the
// normals point out and the signed volume is positive. Faces shared by two voxels are dropped.
// Where two voxels touch only along an edge or at a corner, the mesh keeps them apart: the
// lattice point is split into one mesh vertex per sheet of surface through it, so every edge
// lies in exactly two triangles (a 2-manifold; the split vertices coincide at rest).
//
// Geometry: at rest a lattice point (i, j, k) sits at (i, j, k) L. Deformed, each voxel's corner
// is its centre plus its rotation applied to (+-sx/2, +-sy/2, +-sz/2) of its current size; a mesh
// vertex is the mean of that corner over the distinct voxels whose surface faces meet at the
// vertex. The mesh stays watertight whatever the poses because the topology never changes.
#include <array>
#include <cstdint>
#include <string>
#include <vector>

#include "engine/poses.hpp"
#include "engine/replay.hpp"
#include "evo/experiment/experiment.hpp"

namespace bhm::evo {

struct SurfaceMesh {
    std::vector<std::array<double, 3>> vertices;  //!< metres, world frame
    std::vector<std::array<int, 3>> triangles;    //!< counter-clockwise seen from outside
    std::vector<int> triangle_material;           //!< 1-based material index per triangle
};

//! The surface of a lattice of materials (x fastest, 0 = empty) at rest, voxel edge L.
SurfaceMesh rest_surface(const std::array<int, 3>& size, const std::vector<std::uint8_t>& cells,
                         double voxel_size_m);

//! The surface of a replay's voxels in one pose (frame from the same replay).
SurfaceMesh deformed_surface(const engine::Replay& replay, const engine::VoxelPoses& frame);

//! Enclosed volume by the divergence theorem (positive for outward-wound closed meshes), m^3.
double enclosed_volume(const SurfaceMesh& mesh);

//! Binary STL (little-endian, float32), one facet per triangle with its unit normal.
std::string stl_binary(const SurfaceMesh& mesh);

//! Wavefront OBJ: vertices, then one group per material used ("g NAME" + "usemtl NAME", NAME the
//! material's name with blanks replaced by '_', made unique), referring to mtl_file_name.
std::string obj_document(const SurfaceMesh& mesh, const std::vector<MaterialEntry>& materials,
                         const std::string& mtl_file_name);

//! The MTL file for obj_document: one diffuse colour per material.
std::string mtl_document(const std::vector<MaterialEntry>& materials);

//! OBJ/MTL names of the materials, in palette order (what obj_document and mtl_document use).
std::vector<std::string> obj_material_names(const std::vector<MaterialEntry>& materials);

}  // namespace bhm::evo
