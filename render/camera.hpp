#pragma once
// An orbit camera around a target point, z up. A plain struct: the studio's mouse code calls
// orbit/pan/zoom, the command line picks a named view and frames the workspace.
#include <optional>
#include <string>

#include <glm/mat4x4.hpp>
#include <glm/vec3.hpp>

namespace bhm::render {

//! An axis-aligned box in world metres.
struct Bounds {
    glm::vec3 min{0.0f};
    glm::vec3 max{0.0f};
    bool valid = false;  //!< false until something is added
    void add(const glm::vec3& point);
    void add(const Bounds& other);
    glm::vec3 centre() const { return 0.5f * (min + max); }
    float radius() const;  //!< half the diagonal
};

enum class NamedView {
    Iso,    //!< from above, in front and to the right: three faces visible
    Front,  //!< along -y from the +y side, orthographic (the paper's front section, Figure 13)
    Top,    //!< straight down, orthographic, x right and y up on screen
    Side,   //!< along -x from the +x side (the free end), orthographic
};
std::optional<NamedView> parse_named_view(const std::string& name);
const char* named_view_name(NamedView view);

struct Camera {
    glm::vec3 target{0.0f};
    float yaw_rad = 0.0f;     //!< eye direction from the target, around z from +x
    float pitch_rad = 0.0f;   //!< elevation of the eye above the xy plane, in [-pi/2, pi/2]
    float distance_m = 1.0f;  //!< eye to target (perspective); sets the scale (orthographic)
    float fov_y_rad = 0.6f;   //!< vertical field of view
    bool orthographic = false;
    float scene_radius_m = 1.0f;  //!< size of what is framed, for the clip planes

    glm::vec3 eye_direction() const;  //!< unit vector from target toward the eye
    glm::vec3 forward() const { return -eye_direction(); }
    glm::vec3 right() const;
    glm::vec3 up() const;
    glm::vec3 eye_position() const;
    //! Half the visible height at the target's depth.
    float half_height_m() const;
    glm::mat4 view_matrix() const;
    glm::mat4 projection_matrix(float aspect) const;
    glm::mat4 view_projection(float aspect) const {
        return projection_matrix(aspect) * view_matrix();
    }
};

// Mouse deltas are in window pixels with y down, as GLFW and ImGui report them.
//! Drag by (dx, dy) pixels: yaw follows dx, pitch follows dy (clamped short of the poles).
void orbit(Camera& camera, float dx_px, float dy_px, float radians_per_px = 0.008f);
//! Moves the target so the point under the cursor follows the drag, in a viewport this tall.
void pan(Camera& camera, float dx_px, float dy_px, int viewport_height_px);
//! factor > 1 moves closer (the image grows by factor), < 1 away.
void zoom(Camera& camera, float factor);

//! Keeps the direction, places the target at the centre of bounds and sets the distance so the
//! whole box fits the viewport with a margin (fraction of the view left free on each side).
void frame_bounds(Camera& camera, const Bounds& bounds, float aspect, float margin = 0.06f);
//! A named view framed to bounds.
Camera named_view(NamedView view, const Bounds& bounds, float aspect);

}  // namespace bhm::render
