#pragma once
// Mouse picking in the 3D view: a ray through a pixel, the workspace face it enters through, and
// the lattice cell under the cursor found by walking the ray through the lattice (Amanatides &
// Woo 1987, "A fast voxel traversal algorithm"). Pure geometry on render::Camera, no GL.
#include <array>
#include <functional>
#include <optional>

#include <glm/vec2.hpp>
#include <glm/vec3.hpp>

#include "engine/poses.hpp"
#include "evo/experiment/experiment.hpp"
#include "render/camera.hpp"

namespace bhm::app::gui {

struct Ray {
    glm::vec3 origin{0.0f};
    glm::vec3 direction{0.0f, 0.0f, -1.0f};  //!< unit length
};

//! The ray under pixel (x right, y down, origin at the top-left corner of the viewport).
Ray ray_through_pixel(const render::Camera& camera, glm::vec2 pixel, glm::vec2 viewport_px);

//! Where a world point lands in the viewport (same pixel convention); empty when it is behind the
//! camera.
std::optional<glm::vec2> project_to_pixel(const render::Camera& camera, glm::vec3 point_m,
                                          glm::vec2 viewport_px);

//! The box of a lattice: from the origin to size x voxel_size_m.
struct LatticeBox {
    std::array<int, 3> size{0, 0, 0};
    double voxel_size_m = 0.01;
    glm::vec3 max_corner() const;
    bool contains_cell(const std::array<int, 3>& cell) const;
};

struct FaceHit {
    evo::Face face = evo::Face::XMin;
    float distance_m = 0.0f;  //!< along the ray
    glm::vec3 point_m{0.0f};
};

//! The face the ray enters the box through; empty when it misses or starts inside.
std::optional<FaceHit> pick_box_face(const Ray& ray, const LatticeBox& box);

//! Centre of a face of the box, in metres.
glm::vec3 face_centre_m(const LatticeBox& box, evo::Face face);

//! Cells with coords[axis] > layer are hidden (a cut through the lattice to reach inner cells).
struct Slice {
    int axis = -1;  //!< 0, 1, 2, or -1 for no slice
    int layer = 0;
    bool hides(const std::array<int, 3>& cell) const { return axis >= 0 && cell[axis] > layer; }
};

struct CellHit {
    std::array<int, 3> cell{0, 0, 0};
    bool occupied = false;  //!< true: an occupied cell was hit; false: the fallback cell
};

//! The cell under the ray: the first visible cell along it for which occupied(cell) holds;
//! otherwise the first visible cell of the slice's top layer it crosses (with a slice), or the
//! first visible cell it enters. Empty when the ray misses every visible cell.
std::optional<CellHit> pick_cell(const Ray& ray, const LatticeBox& box, const Slice& slice,
                                 const std::function<bool(const std::array<int, 3>&)>& occupied);

//! Distance along the ray to an oriented box (centre, unit quaternion w x y z, edge lengths
//! along its own axes); empty when it misses. A ray starting inside hits at 0.
std::optional<float> ray_box_distance(const Ray& ray, glm::vec3 centre, const float* quaternion,
                                      glm::vec3 size);

struct VoxelHit {
    int voxel = -1;  //!< index into the poses
    float distance_m = 0.0f;
};
//! The first voxel of a replayed pose the ray hits (each voxel an oriented box of its current
//! size), as drawn; empty when it hits none.
std::optional<VoxelHit> pick_posed_voxel(const Ray& ray, const engine::VoxelPoses& poses);

//! Calls visit(cell) for every cell the ray crosses inside the box, in order, until it returns
//! false.
void walk_cells(const Ray& ray, const LatticeBox& box,
                const std::function<bool(const std::array<int, 3>&)>& visit);

}  // namespace bhm::app::gui
