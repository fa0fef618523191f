#pragma once
// GL side of the 3D view: the renderer plus the framebuffers it draws into (the on-screen view's
// texture and off-screen exports of any size). Lives on the GL thread; needs a current context.
#include <memory>

#include "app/gui/gl_framebuffer.hpp"
#include "render/camera.hpp"
#include "render/draw_list.hpp"
#include "render/image.hpp"
#include "render/renderer.hpp"

namespace bhm::app::gui {

class ViewRenderer {
  public:
    ViewRenderer();
    //! Draws into the view texture (resized as needed) and returns its GL name for ImGui::Image.
    unsigned draw_to_texture(const render::DrawList& list, const render::Camera& camera,
                             int width_px, int height_px, int samples);
    //! Draws off-screen at any size and reads the pixels back (screenshots, frame sequences).
    render::Image draw_to_image(const render::DrawList& list, const render::Camera& camera,
                                int width_px, int height_px, int samples = 4);
    //! Frees the export buffer (large screenshots allocate a lot).
    void release_export_buffer() { export_ = std::make_unique<GlFramebuffer>(); }

  private:
    render::Renderer renderer_;
    GlFramebuffer view_;
    std::unique_ptr<GlFramebuffer> export_ = std::make_unique<GlFramebuffer>();
};

}  // namespace bhm::app::gui
