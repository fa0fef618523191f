#pragma once
// What the renderer is asked to draw: engine-level data only (no evo, no ImGui).
// A Scene is turned into a DrawList on the CPU (draw_list.hpp); GL only uploads and draws that.
#include <array>
#include <cstdint>
#include <optional>
#include <vector>

#include <glm/vec3.hpp>
#include <glm/vec4.hpp>

#include "engine/body_spec.hpp"
#include "engine/poses.hpp"
#include "render/colormap.hpp"

namespace bhm::render {

//! One body on its lattice and its current state. Voxel v sits in lattice cell voxel_cell[v]
//! (x fastest, as in engine::BodySpec); poses holds one pose per voxel, or is empty for "at rest".
struct BodyView {
    int nx = 0, ny = 0, nz = 0;
    double voxel_size_m = 0.01;
    std::vector<std::int32_t> voxel_cell;
    std::vector<std::uint8_t> voxel_material;  //!< 1-based material index
    std::vector<std::uint8_t> voxel_fixed;     //!< 1 = held; may be empty (none held)
    engine::VoxelPoses poses;

    int voxel_count() const { return static_cast<int>(voxel_cell.size()); }
    std::array<int, 3> voxel_coords(int v) const;
};

//! The voxels of a spec (non-empty cells in cell order, the engine's voxel order) at rest.
BodyView body_view_from_spec(const engine::BodySpec& spec);
//! Rest poses: each voxel at its lattice position, cell (x, y, z) centred at (x+0.5, y+0.5, z+0.5)
//! voxel lengths, axis-aligned, full size. The body's lattice starts at the world origin.
engine::VoxelPoses rest_poses(const BodyView& body);
//! Centre of a lattice cell in metres under the same convention.
glm::vec3 cell_centre_m(int x, int y, int z, double voxel_size_m);

//! How a workspace face is marked (paper Figure 2): a fixed boundary plane green, a free one
//! purple, or not drawn.
enum class FaceMarking : std::uint8_t { None, Fixed, Free };

enum class ColorMode : std::uint8_t { Material, Scalar };

struct SceneOptions {
    ColorMode color_mode = ColorMode::Material;
    std::vector<float> voxel_scalar;  //!< (n) one value per voxel, for ColorMode::Scalar
    //! (n) or empty: 1 = the voxel keeps its material colour under ColorMode::Scalar (a field
    //! that some voxels do not have, e.g. the fibre axis of a passive voxel)
    std::vector<std::uint8_t> voxel_without_scalar;
    ScalarRange scalar_range;         //!< values mapped onto the colour map's [0, 1]
    ColorMapName color_map = ColorMapName::Sequential;

    int section_y = -1;  //!< >= 0: voxels with lattice y > section_y are hidden (front section)

    bool show_edges = true;              //!< dark outline on every voxel face, to count voxels
    bool show_workspace_box = true;      //!< wire box around the workspace
    bool show_floor = true;              //!< floor plane with a grid of voxel pitch
    bool show_boundary_faces = true;     //!< fixed (green) and free (purple) workspace faces
    bool show_origin_star = true;        //!< star on the (0,0,0) voxel
    bool show_axes = true;               //!< axes gizmo in the lower left corner
    bool show_legend = true;             //!< colour bar when colouring by scalar
    bool show_ghost = false;             //!< the body at t = 0 as a translucent ghost
    glm::vec3 ghost_offset_m{0.0f};      //!< zero: over the current state; else beside it
    std::vector<glm::vec3> com_trail_m;  //!< centre-of-mass polyline (world, metres); may be empty
};

//! A scene: the body, its workspace and how to colour and decorate it.
struct Scene {
    BodyView body;
    std::array<int, 3> workspace{0, 0, 0};   //!< lattice cells; zero = the body's lattice size
    std::vector<glm::vec4> material_colors;  //!< RGBA per material, index k-1 for material k;
                                             //!< alpha < 1 draws the material translucent
    std::array<FaceMarking, 6> faces{};      //!< x-, x+, y-, y+, z-, z+
    std::optional<engine::VoxelPoses> ghost_poses;  //!< e.g. the t = 0 frame of a replay
    SceneOptions options;
};

//! Default colours: muscle red, tissue pale blue-grey, enclosure translucent grey.
namespace palette {
inline constexpr glm::vec4 kActive{0.86f, 0.27f, 0.22f, 1.0f};
inline constexpr glm::vec4 kPassive{0.66f, 0.76f, 0.86f, 1.0f};
inline constexpr glm::vec4 kEnclosure{0.80f, 0.80f, 0.78f, 0.30f};
inline constexpr glm::vec4 kUnknownMaterial{1.0f, 0.0f, 1.0f, 1.0f};
inline constexpr glm::vec4 kFixedFace{0.18f, 0.72f, 0.30f, 0.22f};
inline constexpr glm::vec4 kFreeFace{0.58f, 0.30f, 0.82f, 0.22f};
inline constexpr glm::vec4 kFixedHatch{0.10f, 0.55f, 0.20f, 1.0f};
inline constexpr glm::vec4 kStar{1.0f, 0.82f, 0.08f, 1.0f};
inline constexpr glm::vec4 kGhost{0.55f, 0.58f, 0.62f, 0.22f};
inline constexpr glm::vec4 kWorkspaceBox{0.30f, 0.32f, 0.36f, 1.0f};
inline constexpr glm::vec4 kFloor{0.90f, 0.91f, 0.92f, 1.0f};
inline constexpr glm::vec4 kGrid{0.74f, 0.76f, 0.79f, 1.0f};
inline constexpr glm::vec4 kComTrail{0.95f, 0.50f, 0.05f, 1.0f};
}  // namespace palette

}  // namespace bhm::render
