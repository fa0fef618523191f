#pragma once
// One studio frame: the tiled layout (no docking in ImGui 1.86: windows are placed every frame and
// their inner edges resize the layout, which the settings remember), the panels, the 3D view, the
// shortcuts and the exports queued by them. Shared by the window and the headless runners.
#include <memory>
#include <string>

#include <imgui.h>

#include "app/gui/studio.hpp"
#include "app/gui/view/renderer.hpp"
#include "app/gui/welcome/thumbnails.hpp"

namespace bhm::app::gui {

//! Fonts and colours (a light theme for figures and papers); scale is the HiDPI factor. Call once
//! after ImGui::CreateContext and before the renderer backend builds the font atlas.
//! Returns the font used ("DejaVu Sans" or "ImGui default").
std::string apply_studio_style(float scale);

//! The colour the runners clear the framebuffer to before ImGui draws: the tiled panels have no
//! backgrounds of their own (see studio_app.cpp).
ImVec4 ui_clear_color();

class StudioApp {
  public:
    //! Needs a current GL context with glad loaded (the renderer compiles its shaders here).
    explicit StudioApp(Studio& studio);

    //! Builds the whole UI for one frame; call between ImGui::NewFrame() and ImGui::Render().
    //! wall_dt_s advances the replay clock.
    void build_frame(double wall_dt_s);

    ViewRenderer& renderer() { return renderer_; }
    Studio& studio() { return studio_; }

  private:
    void layout_and_panels();
    Studio& studio_;
    ViewRenderer renderer_;
    WelcomeThumbnails thumbnails_;  //!< the welcome's, rendered once
    bool design_just_opened_ = false;  //!< the folded left column opened this frame
};

//! Camera and layout into the settings (before they are saved).
void store_view_settings(Studio& studio);
//! Camera angles and zoom from the settings (at start).
void restore_view_settings(Studio& studio);

}  // namespace bhm::app::gui
