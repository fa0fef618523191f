#include "app/gui/welcome/thumbnails.hpp"

#include "app/gui/studio.hpp"
#include "app/gui/view/renderer.hpp"
#include "app/gui/view/viewport.hpp"
#include "app/gui/welcome/example_body.hpp"

namespace bhm::app::gui {

void WelcomeThumbnails::ensure(ViewRenderer& renderer, const std::vector<PresetCard>& cards,
                               int width_px, int height_px, int samples) {
    while (targets_.size() < cards.size()) {
        const PresetCard& card = cards[targets_.size()];
        // What the preset evolves: a generation-0 body in its workspace (the workspace alone
        // when the preset cannot develop one).
        const std::optional<evo::Body> body = example_body(card.experiment);
        const render::DrawList list =
            workspace_draw_list(card.experiment, PainterState{}, body ? &*body : nullptr, true);
        render::Camera camera = iso_camera();
        render::frame_bounds(camera,
                             list.workspace_bounds.valid ? list.workspace_bounds : list.bounds,
                             static_cast<float>(width_px) / static_cast<float>(height_px));
        auto target = std::make_unique<GlFramebuffer>();
        renderer.draw_to_framebuffer(list, camera, *target, width_px, height_px, samples);
        targets_.push_back(std::move(target));
    }
}

unsigned WelcomeThumbnails::texture(std::size_t i) const {
    return i < targets_.size() ? targets_[i]->texture() : 0u;
}

}  // namespace bhm::app::gui
