// The 3D view: a toolbar (mode, named views, display toggles), the scene rendered into a texture
// shown as an ImGui image, camera gestures, painter clicks and a small text overlay.
#include <algorithm>
#include <cfloat>
#include <cmath>
#include <cstdio>
#include <string>

#include <imgui.h>

#include "app/gui/actions/studio_actions.hpp"
#include "app/gui/actions/view_clicks.hpp"
#include "app/gui/panels/panels.hpp"
#include "app/gui/view/renderer.hpp"
#include "app/gui/view/viewport.hpp"
#include "app/gui/widgets/check_badge.hpp"
#include "app/gui/widgets/ui_widgets.hpp"
#include "render/colormap.hpp"

namespace bhm::app::gui {

namespace {

constexpr float kClickSlopPx = 4.0f;  // a press that moves less than this is a click, not a drag

// Continues the toolbar on this line when an item this wide fits, else on the next line.
void next_item(float width) {
    ImGui::SameLine();
    if (ImGui::GetContentRegionAvail().x < width) ImGui::NewLine();
}

float item_width(const char* label, bool box) {
    const ImGuiStyle& style = ImGui::GetStyle();
    return ImGui::CalcTextSize(label).x + style.FramePadding.x * 2.0f +
           (box ? ImGui::GetFrameHeight() + style.ItemInnerSpacing.x : 0.0f);
}

void toolbar(Studio& s) {
    int mode = s.view.mode == ViewMode::Workspace ? 0 : 1;
    if (ImGui::RadioButton("Workspace", &mode, 0)) set_view_mode(s, ViewMode::Workspace);
    record_widget(s, "mode workspace");
    next_item(item_width("Simulation", true));
    if (ImGui::RadioButton("Simulation", &mode, 1)) set_view_mode(s, ViewMode::Simulation);
    record_widget(s, "mode simulation");
    const std::pair<const char*, render::NamedView> views[] = {{"Iso", render::NamedView::Iso},
                                                               {"Front", render::NamedView::Front},
                                                               {"Top", render::NamedView::Top},
                                                               {"Side", render::NamedView::Side}};
    for (const auto& [name, view] : views) {
        next_item(item_width(name, false));
        if (tracked_button(s, name)) set_named_view(s, view);
    }
    next_item(item_width("ortho", true));
    if (ImGui::Checkbox("ortho", &s.view.camera.orthographic)) s.view.camera_needs_framing = true;
    record_widget(s, "ortho");
    next_item(item_width("edges", true));
    ImGui::Checkbox("edges", &s.view.show_edges);
    record_widget(s, "edges");
    if (s.view.mode == ViewMode::Simulation) {
        next_item(item_width("COM trail", true));
        ImGui::Checkbox("COM trail", &s.view.show_trail);
        record_widget(s, "COM trail");
        next_item(item_width("start beside", true));
        if (ImGui::Checkbox("start beside", &s.view.show_start_beside))
            s.view.camera_needs_framing = true;
        record_widget(s, "start beside");
        next_item(ImGui::GetFontSize() * 9.0f);
        ImGui::SetNextItemWidth(ImGui::GetFontSize() * 6.5f);
        int by = static_cast<int>(s.view.color_by);
        if (ImGui::Combo("colour", &by, kColorByNames.data(),
                         static_cast<int>(kColorByNames.size())))
            s.view.color_by = static_cast<ColorBy>(by);
        record_widget(s, "colour");
        if (ImGui::IsItemHovered())
            ImGui::SetTooltip(
                "colour the body by material, displacement from t = 0, volumetric "
                "strain, or the actuation signal of its muscle voxels");
        if (s.bodies.compared) {
            next_item(item_width("split", true));
            if (ImGui::Checkbox("split", &s.view.split)) s.view.camera_needs_framing = true;
            record_widget(s, "split");
            if (ImGui::IsItemHovered())
                ImGui::SetTooltip("the compared body in a pane of its own, with its own camera "
                                  "(off: beside the first, along +y, in one view)");
            if (s.view.split) {
                next_item(item_width("link cameras", true));
                if (ImGui::Checkbox("link cameras", &s.view.link_cameras) &&
                    !s.view.link_cameras)
                    s.view.second.camera = s.view.camera;  // unlinked where it was
                record_widget(s, "link cameras");
                if (ImGui::IsItemHovered())
                    ImGui::SetTooltip("both panes look from the same camera; a drag in either "
                                      "moves both");
            }
        }
    }
}

// The split view's second pane: orbit, pan and zoom of its own camera (or of the main one when
// the cameras are linked); clicks pick nothing there.
void pane_mouse(Studio& s, bool hovered) {
    ImGuiIO& io = ImGui::GetIO();
    auto& p = s.view.second;
    render::Camera& camera = s.view.link_cameras ? s.view.camera : p.camera;
    if (hovered && !p.dragging) {
        for (int b = 0; b < 3; ++b)
            if (ImGui::IsMouseClicked(b)) {
                p.dragging = true;
                p.drag_button = b;
            }
        if (io.MouseWheel != 0.0f) {
            const float factor = std::pow(1.12f, io.MouseWheel);
            render::zoom(camera, factor);
            (s.view.link_cameras ? s.view.zoom : p.zoom) *= factor;
        }
    }
    if (!p.dragging) return;
    const ImVec2 from_press = ImGui::GetMouseDragDelta(p.drag_button, 0.0f);
    const ImVec2 d = ImGui::IsMouseClicked(p.drag_button) ? ImVec2(0.0f, 0.0f) : io.MouseDelta;
    if (std::abs(from_press.x) + std::abs(from_press.y) > kClickSlopPx &&
        (d.x != 0.0f || d.y != 0.0f)) {
        if (p.drag_button == 0)
            render::orbit(camera, d.x, d.y);
        else
            render::pan(camera, d.x, d.y, static_cast<int>(p.size_px.y));
    }
    if (!ImGui::IsMouseDown(p.drag_button)) {
        p.dragging = false;
        p.drag_button = -1;
    }
}

// Lines of text over a pane of the 3D view, from its top-left corner down, each wrapped at the
// pane's width: in the split view a line running past it went under the other pane (issue 39,
// M6). Records the block as the widget `name`.
class OverlayText {
  public:
    OverlayText(Studio& s, const char* name, ImVec2 origin, ImVec2 size)
        : s_(s), name_(name), from_{origin.x + 10.0f, origin.y + 8.0f}, at_(from_),
          wrap_(std::max(40.0f, size.x - 20.0f)), right_(from_.x) {}
    ~OverlayText() {
        s_.ui.widgets[name_] = WidgetRect{{from_.x, from_.y}, {right_, at_.y}, s_.ui.frame};
    }
    //! Returns the line's bottom-right corner (its top-left is at() before the call).
    ImVec2 line(ImU32 color, const std::string& text) {
        ImFont* font = ImGui::GetFont();
        const float size = ImGui::GetFontSize();
        ImGui::GetWindowDrawList()->AddText(font, size, at_, color, text.c_str(), nullptr, wrap_);
        const ImVec2 extent = font->CalcTextSizeA(size, FLT_MAX, wrap_, text.c_str());
        right_ = std::max(right_, at_.x + extent.x);
        const ImVec2 corner{at_.x + extent.x, at_.y + extent.y};
        at_.y += extent.y + ImGui::GetStyle().ItemSpacing.y;
        return corner;
    }
    ImVec2 at() const { return at_; }

  private:
    Studio& s_;
    const char* name_;
    ImVec2 from_, at_;
    float wrap_, right_;
};

void pane_overlay(Studio& s, ImVec2 origin, ImVec2 size) {
    const auto& c = *s.bodies.compared;
    OverlayText text(s, "compared overlay", origin, size);
    text.line(IM_COL32(30, 34, 40, 255), "compared: " + c.label);
    text.line(IM_COL32(90, 96, 106, 255),
              "fitness " + format_fitness(c.fitness, c.experiment.fitness.measure) +
                  (s.view.link_cameras ? "   (cameras linked)" : "   (own camera)"));
}

// The second pane of the split view at [origin, origin + size].
void draw_second_pane(Studio& s, ViewRenderer& renderer, ImVec2 origin, ImVec2 size) {
    auto& p = s.view.second;
    p.origin_px = {origin.x, origin.y};
    p.size_px = {size.x, size.y};
    const render::DrawList list = compared_view_draw_list(s);
    if (s.view.link_cameras) {
        p.camera = s.view.camera;
    } else if (p.needs_framing) {
        const render::Bounds b = list.workspace_bounds.valid ? list.workspace_bounds : list.bounds;
        render::frame_bounds(p.camera, b, size.x / size.y);
        p.camera.distance_m /= std::max(0.05f, p.zoom);
        p.needs_framing = false;
    }
    const ImGuiIO& io = ImGui::GetIO();
    renderer.draw_to_texture(list, p.camera,
                             static_cast<int>(size.x * io.DisplayFramebufferScale.x),
                             static_cast<int>(size.y * io.DisplayFramebufferScale.y),
                             s.view.samples, 1);
    ImGui::SetCursorScreenPos(origin);
    area_button("3d view compared", size,
                ImGuiButtonFlags_MouseButtonLeft | ImGuiButtonFlags_MouseButtonRight |
                    ImGuiButtonFlags_MouseButtonMiddle);
    renderer.add_view_blit(ImGui::GetWindowDrawList(), origin,
                           ImVec2(origin.x + size.x, origin.y + size.y), 1);
    record_widget(s, "3d view compared");
    pane_mouse(s, ImGui::IsItemHovered());
    pane_overlay(s, origin, size);
}

void mouse(Studio& s, glm::vec2 local, bool hovered) {
    ImGuiIO& io = ImGui::GetIO();
    auto& v = s.view;
    if (hovered && !v.dragging) {
        for (int b = 0; b < 3; ++b)
            if (ImGui::IsMouseClicked(b)) {
                v.dragging = true;
                v.drag_button = b;
                v.drag_distance_px = 0.0f;
            }
        if (io.MouseWheel != 0.0f) {
            const float factor = std::pow(1.12f, io.MouseWheel);
            render::zoom(v.camera, factor);
            v.zoom *= factor;
        }
    }
    if (v.dragging) {
        // Measured from where the button went down, not summed from frame deltas: a pointer that
        // jumps to the spot and clicks in one event batch (a fast click, xdotool) moved before the
        // press, and that move is no drag.
        const bool press_frame = ImGui::IsMouseClicked(v.drag_button);
        const ImVec2 from_press = ImGui::GetMouseDragDelta(v.drag_button, 0.0f);
        v.drag_distance_px =
            std::max(v.drag_distance_px, std::abs(from_press.x) + std::abs(from_press.y));
        const ImVec2 d = press_frame ? ImVec2(0.0f, 0.0f) : io.MouseDelta;
        if (v.drag_distance_px > kClickSlopPx && (d.x != 0.0f || d.y != 0.0f)) {
            if (v.drag_button == 0)
                render::orbit(v.camera, d.x, d.y);
            else
                render::pan(v.camera, d.x, d.y, static_cast<int>(v.size_px.y));
        }
        if (!ImGui::IsMouseDown(v.drag_button)) {
            if (v.drag_button == 0 && v.drag_distance_px <= kClickSlopPx && hovered)
                click_in_view(s, local, io.KeyShift);
            v.dragging = false;
            v.drag_button = -1;
        }
    }
}

// The colour map of the scalar field with its range, at the right edge of the view.
void color_bar(const Studio& s, const SimulatedBody& b, ImVec2 origin, ImVec2 size) {
    const auto field = voxel_scalars(s.view.color_by, b.experiment, b.replay,
                                     frame_index_at(b.replay, s.clock.time_s), b.series, b.drive);
    ImDrawList* dl = ImGui::GetWindowDrawList();
    const float w = 14.0f, h = std::min(220.0f, size.y * 0.5f);
    const ImVec2 lo{origin.x + size.x - w - 70.0f, origin.y + 40.0f};
    constexpr int kSteps = 32;
    for (int k = 0; k < kSteps; ++k) {
        const float t0 = float(k) / kSteps, t1 = float(k + 1) / kSteps;
        const glm::vec4 c = render::sample_color_map(field.map, 0.5f * (t0 + t1));
        dl->AddRectFilled({lo.x, lo.y + h * (1.0f - t1)}, {lo.x + w, lo.y + h * (1.0f - t0)},
                          ImGui::ColorConvertFloat4ToU32(ImVec4(c.r, c.g, c.b, 1.0f)));
    }
    dl->AddRect(lo, {lo.x + w, lo.y + h}, IM_COL32(60, 60, 60, 255));
    char text[48];
    const ImU32 dark = IM_COL32(30, 34, 40, 255);
    std::snprintf(text, sizeof text, "%.3g", field.range.max);
    dl->AddText({lo.x + w + 4.0f, lo.y - 6.0f}, dark, text);
    std::snprintf(text, sizeof text, "%.3g", field.range.min);
    dl->AddText({lo.x + w + 4.0f, lo.y + h - 8.0f}, dark, text);
    dl->AddText({lo.x - 10.0f, lo.y + h + 4.0f}, dark,
                kColorByNames[static_cast<std::size_t>(s.view.color_by)]);
    dl->AddText({lo.x - 10.0f, lo.y + h + 4.0f + ImGui::GetFontSize()}, IM_COL32(90, 96, 106, 255),
                field.unit);
}

void overlay(Studio& s, ImVec2 origin, ImVec2 size) {
    ImDrawList* dl = ImGui::GetWindowDrawList();
    const float line = ImGui::GetTextLineHeightWithSpacing();
    OverlayText lines(s, "view overlay", origin, size);
    auto text = [&](ImU32 color, const std::string& t) { lines.line(color, t); };
    const ImU32 dark = IM_COL32(30, 34, 40, 255), dim = IM_COL32(90, 96, 106, 255);
    const auto& e = s.document.experiment();
    char buf[256];
    // A body asked for and not simulated yet (a new champion, a selected row): said first, so
    // the body still playing is never taken for it (issue 25 item 6).
    const std::string pending = s.bodies.simulator.pending_label();
    const bool waiting = !pending.empty() && (!s.bodies.shown || s.bodies.shown->label != pending);
    if (s.view.mode == ViewMode::Simulation && waiting) {
        const ImVec2 from = lines.at();
        text(IM_COL32(190, 110, 0, 255), "simulating " + pending + " ...");
        s.ui.widgets["simulating note"] =
            WidgetRect{{from.x, from.y}, {from.x + size.x * 0.5f, lines.at().y}, s.ui.frame};
    }
    if (s.view.mode == ViewMode::Simulation && s.bodies.shown) {
        const auto& b = *s.bodies.shown;
        const auto measure = b.experiment.fitness.measure;
        text(dark, waiting ? "shown until then: " + b.label : b.label);
        std::snprintf(buf, sizeof buf, "t = %.3f s   fitness %s   bend angle %.2f deg",
                      s.clock.time_s, format_fitness(b.fitness, measure).c_str(),
                      b.bend_angle_deg());
        text(dark, buf);
        if (b.diverged) text(IM_COL32(200, 40, 30, 255), "diverged: " + b.divergence_reason);
        if (const auto* flags = shown_exploits(s); flags && flags->any())
            text(IM_COL32(200, 40, 30, 255), "exploit flags: " + exploit_summary(*flags));
        // CalculiX in the loop: the shown body's badge, the verdict on hover.
        if (const evo::LoopCheck* check =
                s.run.snapshot ? loop_check_of(*s.run.snapshot, b.id) : nullptr) {
            const CheckBadge badge = check_badge(*check);
            const ImVec2 from = lines.at();
            const ImVec2 to = lines.line(ImGui::ColorConvertFloat4ToU32(badge.color),
                                         badge.text + "  (CalculiX in the loop)");
            s.ui.widgets["view check badge"] =
                WidgetRect{{from.x, from.y}, {to.x, to.y}, s.ui.frame};
            if (ImGui::IsMouseHoveringRect(from, to)) ImGui::SetTooltip("%s", badge.tooltip.c_str());
        }
        if (s.bodies.compared && !s.view.split)
            text(dim, "beside (+y): " + s.bodies.compared->label + ", fitness " +
                          format_fitness(s.bodies.compared->fitness,
                                         s.bodies.compared->experiment.fitness.measure));
        if (const FemVerification* v = fem_overlay(s)) {
            const auto& row = v->rows[static_cast<std::size_t>(s.verify.load)];
            text(v->agrees ? IM_COL32(30, 120, 50, 255) : IM_COL32(200, 40, 30, 255),
                 "FEM: " + fem_verdict_line(*v) + "; static at " + row.load +
                     ": ours solid, CalculiX as the grey ghost");
        } else if (s.view.color_by != ColorBy::Material && !b.replay.frames.empty()) {
            color_bar(s, b, origin, size);
        }
        std::snprintf(buf, sizeof buf, "%d voxels, simulated in %.2f s",
                      b.replay.frames.empty() ? 0 : b.replay.frames.front().voxel_count(),
                      b.wall_s);
        text(dim, buf);
    } else {
        std::snprintf(buf, sizeof buf, "%s: workspace %d x %d x %d voxels of %.4g m",
                      e.name.c_str(), e.workspace_size[0], e.workspace_size[1], e.workspace_size[2],
                      e.voxel_size_m);
        text(dark, buf);
        text(dim, s.painter.tool == PainterTool::Faces
                      ? "Faces tool: click a face to cycle free / fixed (green = fixed)"
                      : std::string("Voxels tool: click paints '") +
                            kPaintKindNames[static_cast<std::size_t>(s.painter.brush)] +
                            "', Shift+click clears");
        if (s.view.mode == ViewMode::Simulation && !waiting) text(dim, "no simulated body yet");
    }
    // Bottom line: what is under the cursor.
    std::string under;
    if (s.painter.hovered_face)
        under = std::string("face ") +
                evo::kFaceNames[static_cast<std::size_t>(*s.painter.hovered_face)] + ": " +
                (e.boundary.faces[static_cast<std::size_t>(*s.painter.hovered_face)] ==
                         evo::BoundaryKind::Fixed
                     ? "fixed"
                     : "free");
    if (s.painter.hovered_cell) {
        const auto& c = *s.painter.hovered_cell;
        std::snprintf(buf, sizeof buf, "cell (%d, %d, %d)", c[0], c[1], c[2]);
        under = buf;
        const int o = find_override(e, c);
        if (o >= 0) {
            const auto& ov = e.boundary.voxel_overrides[static_cast<std::size_t>(o)];
            under += ov.kind == evo::OverrideKind::Fixed ? ": fixed"
                     : ov.kind == evo::OverrideKind::Empty
                         ? ": forbidden"
                         : ": material " + std::to_string(ov.material);
        }
    }
    if (!under.empty())
        dl->AddText({origin.x + 10.0f, origin.y + size.y - line - 4.0f}, dark, under.c_str());
    // The clicked voxel, read at the replay time (it follows the clock).
    if (s.view.mode == ViewMode::Simulation) {
        if (const auto r = inspected_voxel(s)) {
            char first[160], second[160];
            static constexpr const char* kAxis[3] = {"x", "y", "z"};
            const std::string fibre = r->fibre_axis >= 0 && r->fibre_axis < 3
                                          ? std::string(", fibres along ") + kAxis[r->fibre_axis]
                                          : std::string();
            std::snprintf(first, sizeof first, "voxel (%d, %d, %d): material %d %s%s%s", r->cell[0],
                          r->cell[1], r->cell[2], r->material, r->material_name.c_str(),
                          r->held ? ", held" : "", fibre.c_str());
            std::snprintf(second, sizeof second,
                          "displacement %.3f voxels   strain %+.4f   actuation %+.3f",
                          r->displacement_vox, r->strain, r->actuation);
            const float w = std::max(ImGui::CalcTextSize(first).x, ImGui::CalcTextSize(second).x);
            const ImVec2 lo{origin.x + 8.0f, origin.y + size.y - 4.0f * line - 6.0f};
            const ImVec2 hi{lo.x + w + 12.0f, lo.y + 2.0f * line + 6.0f};
            dl->AddRectFilled(lo, hi, IM_COL32(255, 255, 255, 225), 3.0f);
            dl->AddRect(lo, hi, IM_COL32(190, 110, 0, 255), 3.0f);
            dl->AddText({lo.x + 6.0f, lo.y + 3.0f}, dark, first);
            dl->AddText({lo.x + 6.0f, lo.y + 3.0f + line}, dark, second);
            s.ui.widgets["voxel inspector"] = WidgetRect{{lo.x, lo.y}, {hi.x, hi.y}, s.ui.frame};
        }
    }
}

}  // namespace

void draw_viewport_panel(Studio& s, ViewRenderer& renderer) {
    toolbar(s);
    const ImVec2 avail = ImGui::GetContentRegionAvail();
    const ImVec2 full{std::max(avail.x, 16.0f), std::max(avail.y, 16.0f)};
    const ImVec2 origin = ImGui::GetCursorScreenPos();
    // Split: the shown body on the left, the compared one on the right, a thin gap between.
    const bool split = split_view_active(s);
    constexpr float kGap = 4.0f;
    const ImVec2 size{split ? std::max(8.0f, (full.x - kGap) * 0.5f) : full.x, full.y};
    s.view.origin_px = {origin.x, origin.y};
    s.view.size_px = {size.x, size.y};

    const ImGuiIO& io = ImGui::GetIO();
    const glm::vec2 local{io.MousePos.x - origin.x, io.MousePos.y - origin.y};
    const bool inside = local.x >= 0 && local.y >= 0 && local.x < size.x && local.y < size.y;
    const bool hovered_window = ImGui::IsWindowHovered();
    update_hover(
        s, hovered_window && inside && !s.view.dragging ? std::optional(local) : std::nullopt);

    render::DrawList list = build_view_draw_list(s);
    frame_view_camera(s, list, size.x / size.y);
    const int fb_w = static_cast<int>(size.x * io.DisplayFramebufferScale.x);
    const int fb_h = static_cast<int>(size.y * io.DisplayFramebufferScale.y);
    renderer.draw_to_texture(list, s.view.camera, fb_w, fb_h, s.view.samples);
    // The image is copied into the UI's framebuffer in draw order; the invisible button owns
    // the mouse over it (ImGui then reports io.WantCaptureMouse, and windows do not drag).
    area_button("3d view", size,
                           ImGuiButtonFlags_MouseButtonLeft | ImGuiButtonFlags_MouseButtonRight |
                               ImGuiButtonFlags_MouseButtonMiddle);
    renderer.add_view_blit(ImGui::GetWindowDrawList(), origin,
                           ImVec2(origin.x + size.x, origin.y + size.y));
    record_widget(s, "3d view");
    // ImGui decides hovering, so a popup or another window over the view keeps the mouse
    // (the io.WantCaptureMouse rule for an embedded view).
    const bool hovered = ImGui::IsItemHovered();
    mouse(s, local, hovered);
    overlay(s, origin, size);
    if (split) {
        draw_second_pane(s, renderer, ImVec2(origin.x + size.x + kGap, origin.y),
                         ImVec2(std::max(8.0f, full.x - size.x - kGap), size.y));
        // Leave the cursor where one full-width view would have left it.
        ImGui::SetCursorScreenPos(ImVec2(origin.x, origin.y + full.y));
    } else {
        s.view.second.needs_framing = true;
    }
}

}  // namespace bhm::app::gui
