#pragma once
// The welcome's preset thumbnails: each preset's workspace with an example body in it (a
// generation-0 body, app/gui/welcome/example_body.hpp) drawn once by our renderer into a framebuffer kept
// for the session, on the UI thread (GL never runs on a worker).
#include <cstddef>
#include <memory>
#include <vector>

#include "app/gui/welcome/welcome.hpp"
#include "app/gui/widgets/gl_framebuffer.hpp"

namespace bhm::app::gui {

class ViewRenderer;

class WelcomeThumbnails {
  public:
    //! Renders the cards not rendered yet (needs the current GL context); cheap afterwards.
    //! `samples`: the 3D view's (1 on a software rasterizer, where 4 cost about twice as much).
    void ensure(ViewRenderer& renderer, const std::vector<PresetCard>& cards, int width_px,
                int height_px, int samples);
    //! The GL texture of card i (bottom row first), 0 when not rendered.
    unsigned texture(std::size_t i) const;
    std::size_t rendered() const { return targets_.size(); }

  private:
    std::vector<std::unique_ptr<GlFramebuffer>> targets_;
};

}  // namespace bhm::app::gui
