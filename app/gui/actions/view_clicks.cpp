#include "app/gui/actions/view_clicks.hpp"

#include "app/gui/actions/studio_actions.hpp"
#include "app/gui/document/constraint_edits.hpp"
#include "app/gui/view/picking.hpp"
#include "app/gui/view/viewport.hpp"
#include "engine/replay.hpp"

namespace bhm::app::gui {

bool click_in_view(Studio& s, glm::vec2 pixel, bool shift) {
    if (s.view.mode == ViewMode::Simulation) {
        s.bodies.inspected_voxel = -1;
        s.bodies.inspected_body.reset();
        if (!s.bodies.shown || s.bodies.shown->replay.frames.empty() || s.view.size_px.x < 1.0f)
            return false;
        const Ray ray = ray_through_pixel(s.view.camera, pixel, s.view.size_px);
        const auto poses = engine::pose_at(s.bodies.shown->replay, s.clock.time_s);
        if (const auto hit = pick_posed_voxel(ray, poses)) {
            s.bodies.inspected_voxel = hit->voxel;
            s.bodies.inspected_body = s.bodies.shown;
        }
        return false;
    }
    if (s.view.mode != ViewMode::Workspace) return false;
    update_hover(s, pixel);
    const auto& p = s.painter;
    if (p.tool == PainterTool::Faces) return p.hovered_face && cycle_face(s, *p.hovered_face);
    if (!p.hovered_cell) return false;
    if (shift) {
        const auto cell = *p.hovered_cell;
        return apply_edit(s, with_override(s.document.experiment(), cell, PaintKind::Clear),
                          paint_edit_label(cell, PaintKind::Clear, 0));
    }
    return paint_cell(s, *p.hovered_cell);
}

}  // namespace bhm::app::gui
