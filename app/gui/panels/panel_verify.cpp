// Analysis > FEM: "Verify in FEM" for the body shown (docs/verify.md): the progress of the
// worker (phase, elapsed time, Cancel), then the verdict, the per-load table of both answers and
// their differences, and which load the 3D view draws with the FEM's shape as a ghost; below,
// the reports kept in the run directory, each of which shows its body with it.
#include <algorithm>
#include <chrono>
#include <cstdio>
#include <optional>
#include <string>

#include <imgui.h>

#include "app/gui/actions/studio_actions.hpp"
#include "app/gui/panels/panels.hpp"
#include "app/gui/widgets/ui_widgets.hpp"

namespace bhm::app::gui {

namespace {

constexpr ImU32 kGood = IM_COL32(30, 120, 50, 255);
constexpr ImU32 kBad = IM_COL32(200, 40, 30, 255);

// How far along the worker is, for the progress bar: CalculiX is most of the time.
float progress_fraction(const FemVerifyState& st) {
    const auto& p = st.progress;
    const float n = static_cast<float>(std::max(p.loads, 1));
    switch (p.phase) {
        case evo::VerifyPhase::Meshing:
            return 0.02f;
        case evo::VerifyPhase::Solving:
            return 0.05f + 0.45f * static_cast<float>(p.load - 1) / n;
        case evo::VerifyPhase::Engine:
            return 0.5f + 0.3f * static_cast<float>(p.load - 1) / n;
        case evo::VerifyPhase::Comparing:
            return 0.8f;
        case evo::VerifyPhase::SecondMesh:  // the mesh error's solve, after the comparison
            return 0.82f + 0.15f * static_cast<float>(p.load - 1) / n;
    }
    return 0.0f;
}

std::string percent(const std::optional<double>& d) {
    if (!d) return "-";
    char buf[32];
    std::snprintf(buf, sizeof buf, "%.1f %%", 100.0 * *d);
    return buf;
}

// A muscle body is checked at rest and at peak activation (bhm verify; docs/verify.md).
bool driven_by_muscle(const evo::Experiment& e) {
    return std::any_of(e.materials.begin(), e.materials.end(), [](const evo::MaterialEntry& m) {
        return m.physics.actuation_model == engine::ActuationModel::Muscle;
    });
}

void pair_cell(double fem, double ours, const std::optional<double>& difference, double tolerance,
               const char* format) {
    char buf[96];
    std::snprintf(buf, sizeof buf, format, fem, ours);
    ImGui::TextUnformatted(buf);
    ImGui::SameLine();
    if (!difference) {
        ImGui::TextDisabled("(-)");
        return;
    }
    ImGui::PushStyleColor(ImGuiCol_Text, *difference <= tolerance ? kGood : kBad);
    ImGui::Text("(%s)", percent(difference).c_str());
    ImGui::PopStyleColor();
}

void progress_section(Studio& s) {
    const auto& st = s.verify.state;
    if (!st) return;
    if (st->phase == FemVerifyPhase::Running) {
        const double elapsed =
            std::chrono::duration<double>(std::chrono::steady_clock::now() - st->started).count();
        char overlay[160];
        std::snprintf(overlay, sizeof overlay, "%s  (%.1f s)", st->step.c_str(), elapsed);
        ImGui::TextUnformatted(st->label.c_str());
        ImGui::ProgressBar(progress_fraction(*st), ImVec2(-1.0f, 0.0f), overlay);
        record_widget(s, "fem progress");
        if (tracked_button(s, "Cancel verification")) cancel_verification(s);
        return;
    }
    char seconds[32];
    std::snprintf(seconds, sizeof seconds, "%.1f s", st->elapsed_s);
    if (st->phase == FemVerifyPhase::Failed) {
        ImGui::PushStyleColor(ImGuiCol_Text, kBad);
        ImGui::TextWrapped("%s", st->error.c_str());
        ImGui::PopStyleColor();
        record_widget(s, "fem error");
    } else if (st->phase == FemVerifyPhase::Cancelled) {
        hint_wrapped("verification of %s cancelled after %s; nothing was written",
                     st->label.c_str(), seconds);
    }
}

void result_section(Studio& s) {
    if (!s.verify.kept_error.empty()) {
        ImGui::PushStyleColor(ImGuiCol_Text, kBad);
        ImGui::TextWrapped("kept report unreadable: %s", s.verify.kept_error.c_str());
        ImGui::PopStyleColor();
    }
    const auto v = s.verify.result;  // shared: the worker may publish a newer one meanwhile
    if (!v) {
        if (s.bodies.shown)
            ImGui::TextDisabled("Not verified yet: Verify in FEM checks it against CalculiX.");
        return;
    }
    ImGui::PushStyleColor(ImGuiCol_Text, !v->compared ? IM_COL32(150, 100, 20, 255)
                                         : v->agrees  ? kGood
                                                      : kBad);
    ImGui::TextWrapped("%s", fem_verdict_line(*v).c_str());
    ImGui::PopStyleColor();
    record_widget(s, "fem verdict");
    if (ImGui::IsItemHovered())
        ImGui::SetTooltip(
            "judged on the experiment's own fitness measure (the largest over the loads);\n"
            "a measure too small to divide by never decides; every measure is in the table.\n"
            "agrees when at most %.0f %% (docs/verify.md)",
            100.0 * v->tolerance);
    if (!v->compared) return;
    // Beside the verdict: how far the FEM's own answer moves with its mesh (absent in reports
    // written before the studio estimated it).
    if (!v->mesh_error.empty()) {
        ImGui::TextWrapped("%s", v->mesh_error.c_str());
        record_widget(s, "fem mesh error");
        if (ImGui::IsItemHovered())
            ImGui::SetTooltip(
                "the deciding measure of the FEM solved again on a second mesh (twice or half\n"
                "the elements per voxel edge): a difference between the models well above it\n"
                "is the models', not the mesh's (docs/verify.md)");
    }
    hint_wrapped("CalculiX %s, %d nodes, %.1f s CPU; ours %.1f s CPU", v->element.c_str(),
                 v->fem_nodes, v->fem_cpu_s, v->engine_cpu_s);
    record_widget(s, "fem cost");
    if (ImGui::IsItemHovered()) ImGui::SetTooltip("the report is kept in %s", v->dir.c_str());
    if (!v->mesh_reason.empty()) {  // the reason names a voxel and can be long
        hint_wrapped("mesh %s", v->mesh_reason.c_str());
        record_widget(s, "fem mesh");
    }
    // Above the table, so that a short tile still shows it.
    if (v->fem_shape.empty()) {
        hint_wrapped("(no shapes.json: nothing to draw in the 3D view)");
    } else {
        ImGui::Checkbox("FEM ghost in the 3D view", &s.verify.ghost);
        record_widget(s, "fem ghost");
        if (ImGui::IsItemHovered())
            ImGui::SetTooltip("our static shape at the chosen load, CalculiX's as the grey ghost");
    }
    hint_wrapped("each cell: CalculiX / ours (difference)");
    if (ImGui::IsItemHovered())
        ImGui::SetTooltip(
            "the relative difference in brackets, green within the tolerance;\n"
            "the radio button picks the load the 3D view draws");
    // Fixed-width columns that scroll sideways: a narrow tile never cuts a number.
    const ImGuiTableFlags flags = ImGuiTableFlags_RowBg | ImGuiTableFlags_BordersOuter |
                                  ImGuiTableFlags_SizingFixedFit | ImGuiTableFlags_ScrollX;
    const float height =
        ImGui::GetTextLineHeightWithSpacing() * (static_cast<float>(v->rows.size()) + 2.5f);
    if (ImGui::BeginTable("fem loads", 5, flags, ImVec2(0.0f, height))) {
        ImGui::TableSetupColumn("load");
        ImGui::TableSetupColumn("tip (mm)");
        ImGui::TableSetupColumn("bend angle (deg)");
        ImGui::TableSetupColumn("COM YZ (mm)");
        ImGui::TableSetupColumn("voxel RMS");
        ImGui::TableHeadersRow();
        for (std::size_t k = 0; k < v->rows.size(); ++k) {
            const auto& r = v->rows[k];
            ImGui::TableNextRow();
            ImGui::TableNextColumn();
            char label[64];
            std::snprintf(label, sizeof label, "%s##fem row", r.load.c_str());
            if (ImGui::RadioButton(label, s.verify.load == static_cast<int>(k)))
                s.verify.load = static_cast<int>(k);
            record_widget(s, "fem load " + r.load);
            if (ImGui::IsItemHovered() && r.load == "peak")  // a muscle body (issue 43)
                ImGui::SetTooltip(
                    "peak: the muscle voxels fully activated (a = 1); a muscle only "
                    "contracts, so there is no -A");
            else if (ImGui::IsItemHovered())
                ImGui::SetTooltip("%s: temperature change %+.3g degC of the active voxels",
                                  r.load.c_str(), r.temperature_c);
            ImGui::TableNextColumn();
            pair_cell(1e3 * r.fem_tip_m, 1e3 * r.engine_tip_m, r.tip, v->tolerance, "%.3g / %.3g");
            ImGui::TableNextColumn();
            pair_cell(r.fem_bend_deg, r.engine_bend_deg, r.bend, v->tolerance, "%.3g / %.3g");
            ImGui::TableNextColumn();
            pair_cell(1e3 * r.fem_com_yz_m, 1e3 * r.engine_com_yz_m, r.com_yz, v->tolerance,
                      "%.3g / %.3g");
            ImGui::TableNextColumn();
            ImGui::TextUnformatted(percent(r.rms).c_str());
        }
        ImGui::EndTable();
    }
    // Under the table, so that the ghost and the loads stay in a short tile.
    if (!v->law.empty()) {
        hint_wrapped("%s", v->law.c_str());
        record_widget(s, "fem law");
        if (ImGui::IsItemHovered())
            ImGui::SetTooltip(
                "a material is only E and nu, so at large strain CalculiX is solved with two laws\n"
                "of those moduli and the verdict judged on the nearer; their spread is how much\n"
                "the answer depends on the tissue's unknown large-strain law (docs/verify.md)");
    }
}

// Every report kept in the run directory: a member's too, which a reopened run does not list.
void kept_section(Studio& s) {
    if (s.verify.kept_reports.empty() || !s.run.snapshot) return;
    ImGui::Separator();
    hint_wrapped("Kept FEM reports (%s/verify): choose one to show its body with it",
                 s.run.snapshot->run_dir.c_str());
    const float right = ImGui::GetWindowPos().x + ImGui::GetWindowContentRegionMax().x;
    const ImGuiStyle& style = ImGui::GetStyle();
    ImGui::PushID("kept reports");
    for (std::size_t k = 0; k < s.verify.kept_reports.size(); ++k) {
        const std::int64_t id = s.verify.kept_reports[k];
        char label[48];
        std::snprintf(label, sizeof label, "#%lld", static_cast<long long>(id));
        const float width = ImGui::CalcTextSize(label).x + 2.0f * style.FramePadding.x;
        if (k > 0 && ImGui::GetItemRectMax().x + style.ItemSpacing.x + width < right)
            ImGui::SameLine();
        const bool shown = s.bodies.shown && s.bodies.shown->id == id;
        if (shown) ImGui::PushStyleColor(ImGuiCol_Button, kGood);
        const bool clicked = ImGui::Button(label);
        if (shown) ImGui::PopStyleColor();
        record_widget(s, "kept report " + std::string(label));
        if (ImGui::IsItemHovered())
            ImGui::SetTooltip("show individual %s with its report and the FEM ghost (no solve)",
                              label);
        if (clicked) show_kept_verification(s, id);
    }
    ImGui::PopID();
}

}  // namespace

void draw_verify_panel(Studio& s) {
    const bool running = s.verify.worker.running();
    ImGui::BeginDisabled(running || !s.bodies.shown);
    if (tracked_button(s, "Verify in FEM")) verify_shown_body(s);
    ImGui::EndDisabled();
    ImGui::SameLine();
    if (s.bodies.shown)
        hint_wrapped("%s against CalculiX at rest, %s", s.bodies.shown->label.c_str(),
                     driven_by_muscle(s.bodies.shown->experiment)
                         ? "and at peak activation (a muscle only contracts)"
                         : "+A and -A");
    else
        hint_wrapped("Select a champion or an individual to verify it.");
    progress_section(s);
    result_section(s);
    kept_section(s);
}

}  // namespace bhm::app::gui
