#pragma once
// The CPU-side draw list: a Scene turned into box instances, lines, triangles and markers.
// Plain data that tests check without GL; the GL renderer only uploads and draws it.
#include <cstdint>
#include <optional>
#include <vector>

#include <glm/vec3.hpp>
#include <glm/vec4.hpp>

#include "render/camera.hpp"
#include "render/colormap.hpp"
#include "render/scene.hpp"

namespace bhm::render {

//! Bits of BoxInstance::flags (read by shaders/box.frag).
enum BoxFlags : std::uint32_t {
    kBoxFixed = 1u,    //!< hatched: the voxel is held
    kBoxGhost = 2u,    //!< the t = 0 ghost: faint outline, no hatch
    kBoxNoEdges = 4u,  //!< no outline
};

//! Bits of BoxInstance::faces: face 2 * axis + (1 for the + side), i.e. x-, x+, y-, y+, z-, z+.
inline constexpr std::uint32_t kAllFaces = 63u;

//! One box: a unit cube scaled by size along its own axes, rotated, then moved to centre.
//! The layout is what the GPU reads per instance (floats only, tightly packed).
struct BoxInstance {
    glm::vec3 centre{0.0f};
    glm::vec4 orientation{1.0f, 0.0f, 0.0f, 0.0f};  //!< unit quaternion w, x, y, z
    glm::vec3 size{0.0f};
    glm::vec4 color{1.0f};
    float flags = 0.0f;              //!< BoxFlags as a float (exact for small integers)
    float faces = float(kAllFaces);  //!< faces to draw (bits as above); 0 = hidden inside
    float voxel = -1.0f;             //!< voxel index in the body (its ghost's too)
};

struct LineVertex {
    glm::vec3 position{0.0f};
    glm::vec4 color{1.0f};
    float width_px = 1.0f;
};

struct TriangleVertex {
    glm::vec3 position{0.0f};
    glm::vec4 color{1.0f};
};

enum class MarkerShape : std::uint8_t { Star, Dot };

//! A screen-facing symbol of constant pixel size, drawn over everything.
struct Marker {
    glm::vec3 position{0.0f};
    glm::vec4 color{1.0f};
    float size_px = 14.0f;  //!< outer radius in a 720-pixel-high picture (scaled with height)
    MarkerShape shape = MarkerShape::Star;
};

//! A colour bar for scalar colouring; the caller may print the numbers next to it.
struct Legend {
    ColorMapName map = ColorMapName::Sequential;
    ScalarRange range;
};

struct DrawList {
    std::vector<BoxInstance> boxes;              //!< opaque, drawn first
    std::vector<BoxInstance> translucent_boxes;  //!< alpha < 1, sorted back to front at draw time
    std::vector<LineVertex> lines;               //!< pairs: segment i is lines[2i], lines[2i+1]
    //! Pairs drawn over everything (the centre-of-mass trail runs inside the body).
    std::vector<LineVertex> lines_on_top;
    std::vector<TriangleVertex> floor;    //!< opaque floor plane, under the grid
    std::vector<LineVertex> floor_lines;  //!< the grid on the floor (pairs, like lines)
    std::vector<TriangleVertex> translucent_triangles;  //!< boundary faces, drawn after boxes
    std::vector<Marker> markers;
    bool axes_gizmo = false;
    std::optional<Legend> legend;
    Bounds bounds;            //!< everything drawn, for framing
    Bounds workspace_bounds;  //!< the workspace box alone

    //! Instances of body voxels (opaque + translucent, no ghost); one per voxel not cut away by
    //! the section, including voxels with every face hidden (faces == 0).
    int voxel_instance_count() const;
};

//! Turns a scene into a draw list. Throws std::invalid_argument when the scene is inconsistent
//! (poses or scalars for a different voxel count, a cell outside the lattice).
DrawList build_draw_list(const Scene& scene);

//! The workspace box of a scene in metres (from the origin to workspace x voxel size).
Bounds workspace_bounds(const Scene& scene);

}  // namespace bhm::render
