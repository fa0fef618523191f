#include "app/gui/view/renderer.hpp"

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
                                       int width_px, int height_px, int samples, int pane) {
    FramebufferRestore restore;
    GlFramebuffer& view = views_[pane == 1 ? 1 : 0];
    view.ensure(width_px, height_px, samples);
    view.bind_for_drawing();
    renderer_.draw(list, camera, view.width(), view.height());
    view.resolve();
    return view.texture();
}

unsigned ViewRenderer::draw_to_framebuffer(const render::DrawList& list,
                                           const render::Camera& camera, GlFramebuffer& target,
                                           int width_px, int height_px, int samples) {
    FramebufferRestore restore;
    target.ensure(width_px, height_px, samples);
    target.bind_for_drawing();
    renderer_.draw(list, camera, target.width(), target.height());
    target.resolve();
    return target.texture();
}

namespace {

// Runs inside ImGui_ImplOpenGL3_RenderDrawData with the UI framebuffer bound for drawing and
// glViewport(0, 0, framebuffer width, height) set by the backend.
void blit_view(const ImDrawList*, const ImDrawCmd* command) {
    const auto& b = *static_cast<const ViewRenderer::Blit*>(command->UserCallbackData);
    if (!b.framebuffer) return;
    GLint viewport[4] = {0, 0, 0, 0}, read = 0;
    glGetIntegerv(GL_VIEWPORT, viewport);
    glGetIntegerv(GL_READ_FRAMEBUFFER_BINDING, &read);
    const GLboolean scissor = glIsEnabled(GL_SCISSOR_TEST);
    glDisable(GL_SCISSOR_TEST);
    glBindFramebuffer(GL_READ_FRAMEBUFFER, b.framebuffer);
    const int x0 = static_cast<int>(b.min.x * b.scale.x);
    const int top = static_cast<int>(b.min.y * b.scale.y);
    const int y0 = viewport[3] - top - b.height;  // GL rows run bottom-up
    glBlitFramebuffer(0, 0, b.width, b.height, x0, y0, x0 + b.width, y0 + b.height,
                      GL_COLOR_BUFFER_BIT, GL_NEAREST);
    glBindFramebuffer(GL_READ_FRAMEBUFFER, static_cast<GLuint>(read));
    if (scissor) glEnable(GL_SCISSOR_TEST);
}

}  // namespace

void ViewRenderer::add_view_blit(ImDrawList* list, ImVec2 min, ImVec2 max, int pane) {
    const int k = pane == 1 ? 1 : 0;
    Blit& blit = blits_[k];
    blit.framebuffer = views_[k].read_framebuffer();
    blit.width = views_[k].width();
    blit.height = views_[k].height();
    blit.min = min;
    blit.max = max;
    blit.scale = ImGui::GetIO().DisplayFramebufferScale;
    list->AddCallback(blit_view, &blit);
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
