#pragma once
// Hidden-face removal for voxel boxes. Software rasterisers pay for every covered pixel of every
// triangle (llvmpipe: depth testing dominates), so a solid block drawn box by box costs its
// depth in overdraw. Faces shared by two neighbours that still meet are left out; voxels
// enclosed on all six sides by opaque neighbours are left out whole.
#include <vector>

#include "render/draw_list.hpp"
#include "render/scene.hpp"

namespace bhm::render {

//! Sets BoxInstance::faces of boxes, all of one body (BoxInstance::voxel indexes body voxels;
//! boxes absent from the list, e.g. cut by a section, count as empty cells). Face f of a box is
//! left out when the neighbouring cell across f holds a box in the list and
//!  - both are opaque and the voxel is enclosed by opaque boxes on all six sides, or
//!  - the two facing faces meet: every pair of matching corners within meet_tolerance x voxel
//!    size (so gaps and steps that open when neighbours bend or swell stay closed by drawing),
//! and the neighbour is opaque or this box is translucent (an opaque face behind a translucent
//! neighbour stays visible).
void cull_hidden_faces(const BodyView& body, std::vector<BoxInstance>& boxes,
                       float meet_tolerance = 0.01f);

//! A vector turned by a unit quaternion (w, x, y, z).
glm::vec3 rotate_vector(const glm::vec4& q, const glm::vec3& v);
//! World position of corner (sx, sy, sz in {-1, 1}) of a box.
glm::vec3 box_corner(const BoxInstance& box, int sx, int sy, int sz);

}  // namespace bhm::render
