// The Constraints panel: the painter's tools (faces, voxel brush, slice), the six faces with their
// kind and enclosure thickness, the overrides, undo / redo, and applying new rules to a run.
#include <string>

#include <imgui.h>

#include "app/gui/actions/studio_actions.hpp"
#include "app/gui/panels/field_editor.hpp"
#include "app/gui/panels/panels.hpp"
#include "app/gui/widgets/ui_widgets.hpp"

namespace bhm::app::gui {

namespace {

void tool_section(Studio& s) {
    auto& p = s.painter;
    int tool = p.tool == PainterTool::Faces ? 0 : 1;
    if (ImGui::RadioButton("Faces (F)", &tool, 0)) set_view_mode(s, ViewMode::Workspace);
    record_widget(s, "tool faces");
    ImGui::SameLine();
    if (ImGui::RadioButton("Voxels (V)", &tool, 1)) set_view_mode(s, ViewMode::Workspace);
    record_widget(s, "tool voxels");
    p.tool = tool == 0 ? PainterTool::Faces : PainterTool::Voxels;
    help_marker(
        "Click in the 3D view (workspace mode). Faces: a click cycles the face under the "
        "cursor between free and fixed. Voxels: a click paints the cell under the cursor "
        "with the brush; Shift+click clears it.");
    if (p.tool == PainterTool::Voxels) {
        int brush = static_cast<int>(p.brush);
        ImGui::RadioButton("fixed", &brush, 0);
        ImGui::SameLine();
        ImGui::RadioButton("forbidden", &brush, 1);
        ImGui::SameLine();
        ImGui::RadioButton("material", &brush, 2);
        ImGui::SameLine();
        ImGui::RadioButton("clear", &brush, 3);
        p.brush = static_cast<PaintKind>(brush);
        if (p.brush == PaintKind::Material) {
            const auto& materials = s.document.experiment().materials;
            p.brush_material = std::clamp(p.brush_material, 1, static_cast<int>(materials.size()));
            ImGui::SetNextItemWidth(field_width() * 1.5f);
            if (ImGui::BeginCombo("Brush material", materials[p.brush_material - 1].name.c_str())) {
                for (std::size_t k = 0; k < materials.size(); ++k)
                    if (ImGui::Selectable(materials[k].name.c_str(),
                                          p.brush_material == int(k) + 1))
                        p.brush_material = static_cast<int>(k) + 1;
                ImGui::EndCombo();
            }
        }
    }
    // The slice hides cells beyond a layer so inner cells can be reached.
    bool slicing = p.slice.axis >= 0;
    if (ImGui::Checkbox("Slice", &slicing)) p.slice.axis = slicing ? 2 : -1;
    if (slicing) {
        const auto& size = s.document.experiment().workspace_size;
        ImGui::SameLine();
        ImGui::SetNextItemWidth(ImGui::GetFontSize() * 3.5f);
        ImGui::Combo("##axis", &p.slice.axis, "x\0y\0z\0");
        ImGui::SameLine();
        ImGui::SetNextItemWidth(-1.0f);
        p.slice.layer = std::clamp(p.slice.layer, 0, size[p.slice.axis] - 1);
        ImGui::SliderInt("##layer", &p.slice.layer, 0, size[p.slice.axis] - 1, "up to layer %d");
    }
    ImGui::Checkbox("Show the champion in the workspace", &p.show_champion);
}

void faces_section(Studio& s) {
    const auto& e = s.document.experiment();
    if (ImGui::BeginTable("faces", 3,
                          ImGuiTableFlags_BordersInnerH | ImGuiTableFlags_SizingStretchProp)) {
        ImGui::TableSetupColumn("face");
        ImGui::TableSetupColumn("boundary");
        ImGui::TableSetupColumn("frame (voxels)");
        ImGui::TableHeadersRow();
        for (int f = 0; f < 6; ++f) {
            const auto face = static_cast<evo::Face>(f);
            ImGui::PushID(f);
            ImGui::TableNextRow();
            ImGui::TableNextColumn();
            ImGui::AlignTextToFramePadding();
            ImGui::TextUnformatted(evo::kFaceNames[static_cast<std::size_t>(f)]);
            ImGui::TableNextColumn();
            const bool fixed =
                e.boundary.faces[static_cast<std::size_t>(f)] == evo::BoundaryKind::Fixed;
            ImGui::PushStyleColor(ImGuiCol_Button, fixed ? ImVec4(0.18f, 0.62f, 0.30f, 0.85f)
                                                         : ImVec4(0.55f, 0.36f, 0.75f, 0.35f));
            if (ImGui::Button(fixed ? "fixed" : "free", ImVec2(-1.0f, 0.0f))) cycle_face(s, face);
            ImGui::PopStyleColor();
            const std::string name = evo::kFaceNames[static_cast<std::size_t>(f)];
            record_widget(s, "face " + name);
            field_tooltip_on_hover(s, "boundary.faces." + name);
            ImGui::TableNextColumn();
            int thickness = e.boundary.enclosure_thickness[static_cast<std::size_t>(f)];
            ImGui::SetNextItemWidth(-1.0f);
            if (ImGui::InputInt("##t", &thickness, 1, 1) &&
                thickness != e.boundary.enclosure_thickness[static_cast<std::size_t>(f)])
                set_enclosure_thickness(s, face, std::max(0, thickness));
            record_widget(s, "frame " + name);
            field_tooltip_on_hover(s, "boundary.enclosure.thickness_voxels." + name);
            ImGui::PopID();
        }
        ImGui::EndTable();
    }
    const auto& materials = e.materials;
    const int frame = e.boundary.enclosure_material;
    ImGui::SetNextItemWidth(field_width() * 1.5f);
    const char* current =
        frame >= 1 && frame <= int(materials.size()) ? materials[frame - 1].name.c_str() : "none";
    const bool choosing = ImGui::BeginCombo("Frame material", current);
    record_widget(s, "frame material");
    field_tooltip_on_hover(s, "boundary.enclosure.material");
    if (choosing) {
        if (ImGui::Selectable("none", frame == 0)) {
            evo::Experiment next = e;
            next.boundary.enclosure_material = 0;
            apply_edit(s, next, "frame material none");
        }
        for (std::size_t k = 0; k < materials.size(); ++k)
            if (ImGui::Selectable(materials[k].name.c_str(), frame == int(k) + 1)) {
                evo::Experiment next = e;
                next.boundary.enclosure_material = static_cast<int>(k) + 1;
                apply_edit(s, next, "frame material " + materials[k].name);
            }
        ImGui::EndCombo();
    }
}

void overrides_section(Studio& s) {
    const auto& overrides = s.document.experiment().boundary.voxel_overrides;
    if (overrides.empty()) {
        ImGui::TextDisabled("no voxel overrides: paint with the Voxels tool");
        return;
    }
    const float height =
        std::min(8, static_cast<int>(overrides.size()) + 1) * ImGui::GetFrameHeightWithSpacing();
    if (ImGui::BeginTable(
            "overrides", 3,
            ImGuiTableFlags_ScrollY | ImGuiTableFlags_RowBg | ImGuiTableFlags_SizingStretchProp,
            ImVec2(0.0f, height))) {
        ImGui::TableSetupScrollFreeze(0, 1);
        ImGui::TableSetupColumn("voxel (x, y, z)");
        ImGui::TableSetupColumn("kind");
        ImGui::TableSetupColumn("", ImGuiTableColumnFlags_WidthFixed);
        ImGui::TableHeadersRow();
        for (std::size_t i = 0; i < overrides.size(); ++i) {
            const auto o = overrides[i];
            ImGui::PushID(static_cast<int>(i));
            ImGui::TableNextRow();
            ImGui::TableNextColumn();
            ImGui::Text("(%d, %d, %d)", o.voxel[0], o.voxel[1], o.voxel[2]);
            ImGui::TableNextColumn();
            if (o.kind == evo::OverrideKind::Material)
                ImGui::Text("material %d", o.material);
            else
                ImGui::TextUnformatted(o.kind == evo::OverrideKind::Fixed ? "fixed" : "forbidden");
            ImGui::TableNextColumn();
            const bool remove = ImGui::SmallButton("remove");
            ImGui::PopID();
            if (remove) {
                apply_edit(s, with_override(s.document.experiment(), o.voxel, PaintKind::Clear),
                           paint_edit_label(o.voxel, PaintKind::Clear, 0));
                break;
            }
        }
        ImGui::EndTable();
    }
}

void history_section(Studio& s) {
    const auto& doc = s.document;
    ImGui::BeginDisabled(!doc.can_undo());
    if (tracked_button(s, "Undo")) undo(s);
    ImGui::EndDisabled();
    if (doc.can_undo() && ImGui::IsItemHovered(ImGuiHoveredFlags_AllowWhenDisabled))
        ImGui::SetTooltip("Ctrl+Z: %s", doc.undo_label().c_str());
    ImGui::SameLine();
    ImGui::BeginDisabled(!doc.can_redo());
    if (tracked_button(s, "Redo")) redo(s);
    ImGui::EndDisabled();
    if (doc.can_redo() && ImGui::IsItemHovered(ImGuiHoveredFlags_AllowWhenDisabled))
        ImGui::SetTooltip("Ctrl+Y: %s", doc.redo_label().c_str());
    ImGui::SameLine();
    ImGui::TextDisabled("%s", doc.can_undo() ? ("last: " + doc.undo_label()).c_str() : "no edits");
}

}  // namespace

void draw_constraints_panel(Studio& s) {
    section_title("Painter");
    tool_section(s);
    section_title("Faces and enclosure");
    faces_section(s);
    section_title("Voxel overrides");
    overrides_section(s);
    section_title("Edit history");
    history_section(s);
    if (rules_differ_from_run(s) || boundary_differs_from_run(s)) section_title("Live run");
    if (rules_differ_from_run(s)) {
        ImGui::TextWrapped(
            "The fitness rules (measure, constraints) or CalculiX checks differ from the "
            "run's. Applying them re-scores the population before the next generation "
            "and marks the change in the fitness plot.");
        if (tracked_button(s, "Apply to run")) apply_rules_to_run(s);
    }
    if (boundary_differs_from_run(s))
        ImGui::TextWrapped(
            "Faces, frame and overrides differ from the run's: they change the "
            "bodies, so they apply to the next run (Stop, then Start).");
}

}  // namespace bhm::app::gui
