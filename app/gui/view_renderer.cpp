#include "app/gui/view_renderer.hpp"

#include <glad/gl.h>

namespace bhm::app::gui {

namespace {

// The renderer leaves GL state the ImGui backend sets itself; but the previous framebuffer
// binding must come back so ImGui draws into the window / off-screen target again.
struct FramebufferRestore {
    GLint draw = 0, read = 0;
    GLint viewport[4] = {0, 0, 0, 0};
    FramebufferRestore() {
        glGetIntegerv(GL_DRAW_FRAMEBUFFER_BINDING, &draw);
        glGetIntegerv(GL_READ_FRAMEBUFFER_BINDING, &read);
        glGetIntegerv(GL_VIEWPORT, viewport);
    }
    ~FramebufferRestore() {
        glBindFramebuffer(GL_DRAW_FRAMEBUFFER, static_cast<GLuint>(draw));
        glBindFramebuffer(GL_READ_FRAMEBUFFER, static_cast<GLuint>(read));
        glViewport(viewport[0], viewport[1], viewport[2], viewport[3]);
    }
};

}  // namespace

ViewRenderer::ViewRenderer() = default;

unsigned ViewRenderer::draw_to_texture(const render::DrawList& list, const render::Camera& camera,
                                       int width_px, int height_px, int samples) {
    FramebufferRestore restore;
    view_.ensure(width_px, height_px, samples);
    view_.bind_for_drawing();
    renderer_.draw(list, camera, view_.width(), view_.height());
    view_.resolve();
    return view_.texture();
}

render::Image ViewRenderer::draw_to_image(const render::DrawList& list,
                                          const render::Camera& camera, int width_px, int height_px,
                                          int samples) {
    FramebufferRestore restore;
    export_->ensure(width_px, height_px, samples);
    export_->bind_for_drawing();
    renderer_.draw(list, camera, export_->width(), export_->height());
    export_->resolve();
    return export_->read_image();
}

}  // namespace bhm::app::gui
