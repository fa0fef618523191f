#pragma once
// Draws a DrawList with OpenGL 3.3 core into the framebuffer that is bound (a GLFW window's or
// the OSMesa target's). Needs a current context with glad loaded (window.hpp, offscreen.hpp).
#include <memory>

#include <glm/vec3.hpp>

#include "render/camera.hpp"
#include "render/draw_list.hpp"

namespace bhm::render {

struct RenderStyle {
    glm::vec3 background_top{0.985f, 0.988f, 0.992f};
    glm::vec3 background_bottom{0.86f, 0.88f, 0.91f};
    float edge_half_width_px = 0.6f;  //!< voxel outlines
    bool check_errors = true;         //!< glGetError after each frame; throws on any error
};

class Renderer {
  public:
    //! Compiles the shaders and creates the buffers; throws std::runtime_error naming the shader
    //! file and the driver log on a compile or link error.
    explicit Renderer(RenderStyle style = {});
    ~Renderer();
    Renderer(const Renderer&) = delete;
    Renderer& operator=(const Renderer&) = delete;

    //! Clears and draws into the bound framebuffer, viewport (0, 0, width, height).
    void draw(const DrawList& list, const Camera& camera, int width_px, int height_px);

    RenderStyle& style() { return style_; }

  private:
    struct Gl;
    std::unique_ptr<Gl> gl_;
    RenderStyle style_;
};

}  // namespace bhm::render
