#pragma once
// GL side of the 3D view: the renderer plus the framebuffers it draws into (the on-screen view's
// texture and off-screen exports of any size). Lives on the GL thread; needs a current context.
#include <memory>

#include <imgui.h>

#include "app/gui/widgets/gl_framebuffer.hpp"
#include "render/camera.hpp"
#include "render/draw_list.hpp"
#include "render/image.hpp"
#include "render/renderer.hpp"

namespace bhm::app::gui {

class ViewRenderer {
  public:
    ViewRenderer();
    //! Draws into the view texture (resized as needed) and returns its GL name for ImGui::Image.
    //! Pane 1 is the split view's second pane (a compared body), with a texture of its own.
    unsigned draw_to_texture(const render::DrawList& list, const render::Camera& camera,
                             int width_px, int height_px, int samples, int pane = 0);
    //! Draws off-screen at any size and reads the pixels back (screenshots, frame sequences).
    render::Image draw_to_image(const render::DrawList& list, const render::Camera& camera,
                                int width_px, int height_px, int samples = 4);
    //! Queues a copy of the view drawn by draw_to_texture into the UI's framebuffer over the
    //! rectangle [min, max] (ImGui coordinates), in the draw order of `list` (an ImDrawList
    //! callback, so ImGui draws its overlays after it). On a software rasterizer a framebuffer
    //! blit costs a fraction of a textured, blended quad of the same size.
    void add_view_blit(ImDrawList* list, ImVec2 min, ImVec2 max, int pane = 0);

    //! Draws into a framebuffer the caller keeps (the welcome's thumbnails) and returns its
    //! texture (bottom row first).
    unsigned draw_to_framebuffer(const render::DrawList& list, const render::Camera& camera,
                                 GlFramebuffer& target, int width_px, int height_px, int samples);

    //! Frees the export buffer (large screenshots allocate a lot).
    void release_export_buffer() { export_ = std::make_unique<GlFramebuffer>(); }

    struct Blit {
        unsigned framebuffer = 0;
        int width = 0, height = 0;    //!< source, in pixels
        ImVec2 min{0, 0}, max{0, 0};  //!< destination, ImGui coordinates
        ImVec2 scale{1, 1};           //!< framebuffer pixels per ImGui unit
    };

  private:
    render::Renderer renderer_;
    Blit blits_[2];
    GlFramebuffer views_[2];
    std::unique_ptr<GlFramebuffer> export_ = std::make_unique<GlFramebuffer>();
};

}  // namespace bhm::app::gui
