// The Experiment panel: every field of the experiment with its unit and range, File actions and
// recent files. Fields come from the experiment table (evo/experiment/experiment_fields.hpp)
// through field_editor.hpp: they edit studio.draft and commit through the validator.
#include <string>
#include <string_view>

#include <imgui.h>

#include "app/gui/actions/draft_edits.hpp"
#include "app/gui/actions/studio_actions.hpp"
#include "app/gui/actions/unsaved_guard.hpp"
#include "app/gui/panels/field_editor.hpp"
#include "app/gui/panels/file_dialog_widget.hpp"
#include "app/gui/panels/material_picker.hpp"
#include "app/gui/panels/panels.hpp"
#include "app/gui/panels/twitch_plot.hpp"
#include "app/gui/widgets/ui_widgets.hpp"
#include "evo/experiment/experiment_fields.hpp"
#include "evo/experiment/validated_envelope.hpp"

namespace bhm::app::gui {

namespace {

void file_section(Studio& s) {
    ImGui::SetNextItemWidth(-1.0f);
    char buffer[1024];
    std::snprintf(buffer, sizeof buffer, "%s", s.path_field.c_str());
    if (ImGui::InputTextWithHint("##path", "experiment file path (.json)", buffer, sizeof buffer,
                                 ImGuiInputTextFlags_EnterReturnsTrue)) {
        s.path_field = buffer;
        request_open_experiment(s, s.path_field);
    } else if (ImGui::IsItemEdited()) {
        s.path_field = buffer;
    }
    record_widget(s, "path");
    if (tracked_button(s, "New")) request_new_experiment(s);
    ImGui::SameLine();
    // "Open..." and "Save As..." browse (file_dialog.hpp); a path typed above is taken by the
    // dialog's name field too, and Enter in the path field opens it.
    if (tracked_button(s, "Open...")) show_file_dialog(s, FileDialogPurpose::OpenExperiment);
    ImGui::SameLine();
    if (tracked_button(s, "Save")) save_experiment(s);
    ImGui::SameLine();
    if (tracked_button(s, "Save As...")) show_file_dialog(s, FileDialogPurpose::SaveExperimentAs);
    ImGui::SameLine();
    ImGui::SetNextItemWidth(-1.0f);
    if (ImGui::BeginCombo("##recent", "Recent", ImGuiComboFlags_HeightLarge)) {
        if (s.settings.recent_files.empty()) ImGui::TextDisabled("no recent files");
        for (const auto& path : s.settings.recent_files) {
            if (ImGui::Selectable(path.c_str())) {
                s.path_field = path;
                request_open_experiment(s, std::string(path));
                break;  // the list changed
            }
        }
        ImGui::EndCombo();
    }
}

void workspace_section(Studio& s) {
    if (experiment_field(s, "workspace.size")) s.view.camera_needs_framing = true;
    experiment_field(s, "workspace.voxel_size_m");
    ImGui::PushStyleColor(ImGuiCol_Text, ImGui::GetStyleColorVec4(ImGuiCol_TextDisabled));
    ImGui::TextWrapped("design space = workspace minus the enclosure frame (Constraints tab)");
    ImGui::PopStyleColor();
}

void materials_section(Studio& s) {
    auto& materials = s.draft.materials;
    for (std::size_t k = 0; k < materials.size(); ++k) {
        auto& m = materials[k];
        ImGui::PushID(static_cast<int>(k));
        float color[3] = {m.color[0], m.color[1], m.color[2]};
        const std::string title = std::to_string(k + 1) + ". " + m.name +
                                  (m.active() ? "  (active)" : "  (passive)") + "###material";
        ImGui::ColorButton("##swatch", ImVec4(color[0], color[1], color[2], 1.0f),
                           ImGuiColorEditFlags_NoTooltip,
                           ImVec2(ImGui::GetFontSize(), ImGui::GetFontSize()));
        ImGui::SameLine();
        if (ImGui::TreeNodeEx(title.c_str(), ImGuiTreeNodeFlags_DefaultOpen)) {
            if (field_text("##name", m.name, "material name")) commit_draft(s, "material name");
            material_library_picker(s, k);
            const std::string idx = std::to_string(k + 1);
            const bool muscle = m.physics.actuation_model == engine::ActuationModel::Muscle;
            for (const auto& f : evo::material_fields()) {
                // The muscle model's fields only where it drives the material (issue 43).
                if (f.parent() == "muscle" && !muscle) continue;
                if (std::string_view(f.path) == "cte_per_c" && muscle) continue;
                material_field(s, k, f.path);
            }
            if (muscle) draw_twitch_plot(s, k, m.physics.muscle);
            ImGui::SetNextItemWidth(field_width());
            if (ImGui::ColorEdit3("Colour", color, ImGuiColorEditFlags_NoInputs)) {
                m.color = {color[0], color[1], color[2]};
                m.has_color = true;
            }
            if (ImGui::IsItemDeactivatedAfterEdit()) commit_draft(s, "material " + idx + " colour");
            if (materials.size() > 1 && ImGui::SmallButton("Remove material")) {
                materials.erase(materials.begin() + static_cast<long>(k));
                commit_draft(s, "remove material " + idx);
                ImGui::TreePop();
                ImGui::PopID();
                return;
            }
            ImGui::TreePop();
        }
        ImGui::PopID();
    }
    // Outside the envelope docs/physics.md validates: a warning, as `bhm validate` prints it.
    for (const auto& w : evo::envelope_warnings(s.draft, nullptr, "")) {
        ImGui::PushStyleColor(ImGuiCol_Text, ImVec4(0.95f, 0.75f, 0.3f, 1.0f));
        ImGui::TextWrapped("%s: %s", w.field.c_str(), w.message.c_str());
        ImGui::PopStyleColor();
    }
    if (tracked_button(s, "Add material") &&
        materials.size() < static_cast<std::size_t>(evo::kMaxMaterials)) {
        evo::MaterialEntry m;
        m.name = "material " + std::to_string(materials.size() + 1);
        materials.push_back(m);
        commit_draft(s, "add material");
    }
}

void actuation_section(Studio& s) {
    for (const char* path :
         {"actuation.frequency_hz", "actuation.temperature_amplitude_c", "actuation.phase",
          "actuation.phase_offset_rad", "environment.gravity_m_s2", "environment.floor"})
        experiment_field(s, path);
}

void simulation_section(Studio& s) {
    for (const char* path :
         {"simulation.settle_s", "simulation.evaluate_s", "simulation.dt_fraction",
          "simulation.rotary_inertia_scale", "simulation.bond_damping_ratio",
          "simulation.global_damping_ratio", "simulation.collision_damping_ratio",
          "simulation.implicit_damping_sweeps", "simulation.record_fps",
          "simulation.end_when_periodic", "simulation.periodic_tolerance"})
        experiment_field(s, path);
}

void fitness_section(Studio& s) {
    for (const char* path :
         {"fitness.measure", "fitness.minimize_active_voxels", "fitness.volume_objective",
          "fitness.constraints.attached_to_fixed_face", "fitness.constraints.min_fill_fraction",
          "fitness.constraints.min_active_voxels"})
        experiment_field(s, path);
    // The exploit flags (E, D, T in the Population panel) can be forbidden, not only seen: a
    // flagged body then scores as invalid (docs/evolution.md, Exploit flags).
    ImGui::TextDisabled("Reject bodies flagged as");
    experiment_field(s, "fitness.constraints.reject_escaped");
    record_widget(s, "reject escaped");
    experiment_field(s, "fitness.constraints.reject_detached_motion");
    record_widget(s, "reject detached motion");
    experiment_field(s, "fitness.constraints.reject_tentacle");
    record_widget(s, "reject tentacle");
}

// Every field of the table under `prefix` ("evolution.neat."), in the table's order.
void fields_under(Studio& s, std::string_view prefix) {
    for (const auto& f : evo::experiment_fields())
        if (std::string_view(f.path).starts_with(prefix)) experiment_field(s, f.path);
}

void evolution_section(Studio& s) {
    const auto& ev = s.draft.evolution;
    experiment_field(s, "evolution.algorithm");
    if (ev.algorithm == evo::Algorithm::Afpo || ev.algorithm == evo::Algorithm::Novelty ||
        ev.algorithm == evo::Algorithm::Ga)
        experiment_field(s, "evolution.crossover_rate");
    // What evolves (issue 44): the body and controller list are set in the file or by
    // bhm evolve --body (docs/experiment-format.md, "Controllers").
    experiment_field(s, "evolution.controller.mode");
    // The parameters of the chosen algorithm: NEAT's (HyperNEAT's too), the HyperNEAT
    // substrate's and novelty's (docs/evolution.md, docs/hyperneat.md).
    if (evo::uses_neat(ev.algorithm)) fields_under(s, "evolution.neat.");
    if (ev.algorithm == evo::Algorithm::HyperNeat) fields_under(s, "evolution.hyperneat.");
    if (ev.algorithm == evo::Algorithm::Novelty) fields_under(s, "evolution.novelty.");
    for (const char* path :
         {"evolution.population", "evolution.generations", "evolution.wall_budget_h",
          "evolution.max_neutral_retries", "evolution.seed", "evolution.threads"})
        experiment_field(s, path);
    fields_under(s, "evolution.cppn.");
    // CalculiX in the loop (docs/verify.md): unlike the fields above, a live run takes these
    // between generations, as a rule change, when they are sent.
    ImGui::TextDisabled("CalculiX in the loop");
    fields_under(s, "evolution.verify.");
    if (verify_differs_from_run(s)) {
        ImGui::TextWrapped(
            "These differ from the live run's: Apply (or Resume) sends them, and "
            "they take effect from its next generation.");
        if (tracked_button(s, "Apply checks to run")) apply_rules_to_run(s);
    }
}

}  // namespace

void draw_experiment_panel(Studio& s) {
    sync_draft(s);
    file_section(s);
    ImGui::Separator();
    experiment_field(s, "name");
    experiment_field(s, "description", true);
    const ImGuiTreeNodeFlags open = ImGuiTreeNodeFlags_DefaultOpen;
    if (ImGui::CollapsingHeader("Workspace", open)) workspace_section(s);
    const bool materials_open = ImGui::CollapsingHeader("Materials");
    record_widget(s, "header Materials");
    if (materials_open) materials_section(s);
    const bool actuation_open = ImGui::CollapsingHeader("Actuation and environment");
    record_widget(s, "header Actuation");
    if (actuation_open) actuation_section(s);
    if (ImGui::CollapsingHeader("Simulation timing", open)) simulation_section(s);
    if (ImGui::CollapsingHeader("Fitness", open)) fitness_section(s);
    const bool evolution_open = ImGui::CollapsingHeader("Evolution (algorithm, CPPN)");
    record_widget(s, "header Evolution");
    if (evolution_open) evolution_section(s);
}

}  // namespace bhm::app::gui
