// The Experiment panel: every field of the experiment with its unit and range, File actions and
// recent files. Fields edit studio.draft and commit through the validator (ui_widgets.hpp).
#include <string>

#include <imgui.h>

#include "app/gui/panels/panels.hpp"
#include "app/gui/studio_actions.hpp"
#include "app/gui/unsaved_guard.hpp"
#include "app/gui/widgets/material_picker.hpp"
#include "app/gui/widgets/ui_widgets.hpp"
#include "evo/experiment/validated_envelope.hpp"

namespace bhm::app::gui {

namespace {

void file_section(Studio& s) {
    ImGui::SetNextItemWidth(-1.0f);
    char buffer[1024];
    std::snprintf(buffer, sizeof buffer, "%s", s.path_field.c_str());
    if (ImGui::InputTextWithHint("##path", "experiment file path (.json)", buffer, sizeof buffer))
        s.path_field = buffer;
    record_widget(s, "path");
    if (tracked_button(s, "New")) request_new_experiment(s);
    ImGui::SameLine();
    if (tracked_button(s, "Open")) request_open_experiment(s, s.path_field);
    ImGui::SameLine();
    if (tracked_button(s, "Save")) save_experiment(s);
    ImGui::SameLine();
    if (tracked_button(s, "Save As")) save_experiment_as(s, s.path_field);
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
    auto& e = s.draft;
    ImGui::SetNextItemWidth(field_width());
    ImGui::InputInt3("Workspace", e.workspace_size.data());
    const bool size_done = ImGui::IsItemDeactivatedAfterEdit();
    if (ImGui::IsItemHovered())
        ImGui::SetTooltip(
            "lattice size in voxels (x, y, z), each 1..255; paper exp. 3: 20 x 8 x 7");
    ImGui::SameLine();
    ImGui::TextDisabled("voxels");
    if (size_done) {
        s.view.camera_needs_framing = true;
        commit_draft(s, "workspace size");
    }
    if (field_double("Voxel size", e.voxel_size_m, "m",
                     "edge length of one voxel, [1e-6, 10] m; paper: 0.01 m"))
        commit_draft(s, "voxel size");
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
            if (field_double("E", m.physics.youngs_modulus_pa, "Pa",
                             "Young's modulus, (0, 1e12] Pa; paper Table 1: 5e6", "%.4g"))
                commit_draft(s, "material " + idx + " Young's modulus");
            if (field_double("Density", m.physics.density_kg_m3, "kg/m^3", "> 0; paper: 1000",
                             "%.4g"))
                commit_draft(s, "material " + idx + " density");
            if (field_double("Poisson", m.physics.poisson_ratio, "-", "(-1, 0.5); paper: 0.35",
                             "%.3f"))
                commit_draft(s, "material " + idx + " Poisson ratio");
            if (field_double("CTE", m.physics.cte_per_c, "1/degC",
                             "[0, 1]; > 0 makes it active (muscle); paper: 0.01", "%.4g"))
                commit_draft(s, "material " + idx + " CTE");
            if (field_double("Static friction", m.physics.static_friction, "-", ">= 0; paper: 1",
                             "%.3f"))
                commit_draft(s, "material " + idx + " static friction");
            if (field_double("Dynamic friction", m.physics.dynamic_friction, "-",
                             "[0, static]; paper: 0.5", "%.3f"))
                commit_draft(s, "material " + idx + " dynamic friction");
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
    if (tracked_button(s, "Add material") && materials.size() < 9) {
        evo::MaterialEntry m;
        m.name = "material " + std::to_string(materials.size() + 1);
        materials.push_back(m);
        commit_draft(s, "add material");
    }
}

void actuation_section(Studio& s) {
    auto& a = s.draft.actuation;
    if (field_double("Frequency", a.frequency_hz, "Hz", "[0, 1000]; paper Table 1: 2 Hz", "%.4g"))
        commit_draft(s, "actuation frequency");
    if (field_double("Amplitude", a.temperature_amplitude_c, "degC",
                     "temperature swing; cte x amplitude < 0.9; Kriegman 2020: 14.47", "%.4g"))
        commit_draft(s, "actuation amplitude");
    int phase = a.phase == evo::PhaseMode::Uniform ? 0 : 1;
    ImGui::SetNextItemWidth(field_width());
    if (ImGui::Combo("Phase", &phase, "uniform\0random\0")) {
        a.phase = phase == 0 ? evo::PhaseMode::Uniform : evo::PhaseMode::Random;
        commit_draft(s, "actuation phase");
    }
    if (field_double("Phase offset", a.phase_offset_rad, "rad",
                     "[-pi, pi], added to every voxel's phase: a prototype's lag behind its drive "
                     "(bhm calibrate's phase_lag)",
                     "%.4g"))
        commit_draft(s, "actuation phase offset");
    auto& env = s.draft.environment;
    if (field_double("Gravity", env.gravity_m_s2, "m/s^2",
                     "along z, [-1000, 1000]; -9.81 pulls down", "%.4g"))
        commit_draft(s, "gravity");
    if (field_bool("Floor at z = 0", env.floor, "penalty contact with Coulomb friction"))
        commit_draft(s, "floor");
}

void simulation_section(Studio& s) {
    auto& sim = s.draft.simulation;
    if (field_double("Settle", sim.settle_s, "s", "gravity only, actuation off; paper: 1 s",
                     "%.4g"))
        commit_draft(s, "settle time");
    if (field_double("Evaluate", sim.evaluate_s, "s", "actuated time; paper: 10 s", "%.4g"))
        commit_draft(s, "evaluation time");
    if (field_double("dt fraction", sim.dt_fraction, "-", "(0, 1] of the largest stable step",
                     "%.3f"))
        commit_draft(s, "dt fraction");
    if (field_double("Bond damping", sim.bond_damping_ratio, "x crit.", "[0, 10]; 1.0", "%.3f"))
        commit_draft(s, "bond damping");
    if (field_double("Global damping", sim.global_damping_ratio, "x crit.", "[0, 10]; 0.01",
                     "%.3f"))
        commit_draft(s, "global damping");
    if (field_double("Collision damping", sim.collision_damping_ratio, "x crit.", "[0, 10]; 0.8",
                     "%.3f"))
        commit_draft(s, "collision damping");
    if (field_double("Record rate", sim.record_fps, "frames/s",
                     "(0, 1000]; replays and fitness samples", "%.4g"))
        commit_draft(s, "record rate");
}

void fitness_section(Studio& s) {
    auto& f = s.draft.fitness;
    int measure = static_cast<int>(f.measure);
    ImGui::SetNextItemWidth(field_width() * 1.4f);
    if (ImGui::Combo("Measure", &measure,
                     "com_final_3d (voxels)\0com_final_yz (voxels)\0com_max_3d (voxels)\0"
                     "com_max_yz (voxels)\0bend_angle_deg (deg)\0")) {
        f.measure = static_cast<evo::FitnessMeasure>(measure);
        commit_draft(s, "fitness measure");
    }
    if (field_bool("Minimise active voxels", f.minimize_active_voxels, "third AFPO objective"))
        commit_draft(s, "minimise active voxels");
    if (field_bool("Attached to fixed face", f.constraints.attached_to_fixed_face,
                   "the body must touch every fixed face (paper section 4.1)"))
        commit_draft(s, "attachment constraint");
    if (field_double("Min fill", f.constraints.min_fill_fraction, "fraction",
                     "[0, 1] of the design space", "%.3f"))
        commit_draft(s, "minimum fill fraction");
    if (field_int("Min active", f.constraints.min_active_voxels, "voxels", ">= 0 active voxels"))
        commit_draft(s, "minimum active voxels");
    // The exploit flags (E, D, T in the Population panel) can be forbidden, not only seen: a
    // flagged body then scores as invalid (docs/evolution.md, Exploit flags).
    ImGui::TextDisabled("Reject bodies flagged as");
    if (field_bool("escaped (E)", f.constraints.reject_escaped,
                   "voxels not held by a fixed face, directly or through neighbours; checked "
                   "before simulating, so such bodies are never simulated"))
        commit_draft(s, "reject escaped");
    record_widget(s, "reject escaped");
    if (field_bool("detached motion (D)", f.constraints.reject_detached_motion,
                   "the body moves but its part next to the fixed face barely does; scored -2"))
        commit_draft(s, "reject detached motion");
    record_widget(s, "reject detached motion");
    if (field_bool("tentacle (T)", f.constraints.reject_tentacle,
                   "thin voxels (at most 2 filled neighbours) carry most of the motion; scored -2"))
        commit_draft(s, "reject tentacle");
    record_widget(s, "reject tentacle");
}

//! NEAT's parameters (docs/evolution.md#neat), shown when the algorithm is "neat".
void neat_fields(Studio& s) {
    auto& n = s.draft.evolution.neat;
    if (field_double("NEAT c1", n.c1, "", "[0, 100]: weight of excess genes; 1", "%.3g"))
        commit_draft(s, "NEAT c1");
    if (field_double("NEAT c2", n.c2, "", "[0, 100]: weight of disjoint genes; 1", "%.3g"))
        commit_draft(s, "NEAT c2");
    if (field_double("NEAT c3", n.c3, "", "[0, 100]: weight of the mean weight difference; 0.4",
                     "%.3g"))
        commit_draft(s, "NEAT c3");
    if (field_bool("NEAT divide by N", n.normalize_by_size,
                   "divide E and D by the larger gene count from 20 genes on (the paper's)"))
        commit_draft(s, "NEAT size normalisation");
    if (field_double("Compat. threshold", n.compatibility_threshold, "delta",
                     "(0, 1000]: closer than this to a representative joins its species; 3",
                     "%.3g"))
        commit_draft(s, "NEAT compatibility threshold");
    if (field_int("Target species", n.target_species, "",
                  "[0, 100000]: the threshold moves toward this many; 0 = fixed; 5"))
        commit_draft(s, "NEAT target species");
    if (field_double("Threshold step", n.threshold_step, "delta", "(0, 100]; 0.3", "%.3g"))
        commit_draft(s, "NEAT threshold step");
    if (field_double("Survival", n.survival_fraction, "fraction",
                     "(0, 1]: best share of a species that parents; 0.2", "%.3g"))
        commit_draft(s, "NEAT survival fraction");
    if (field_int("Elitism", n.elitism, "per species", "best members copied unchanged; 1"))
        commit_draft(s, "NEAT elitism");
    if (field_int("Stagnation", n.stagnation_generations, "generations",
                  "no improvement this long: no more offspring; 15"))
        commit_draft(s, "NEAT stagnation");
    if (field_double("NEAT crossover", n.crossover_rate, "",
                     "[0, 1]: share of offspring made by crossover; 0.75", "%.3g"))
        commit_draft(s, "NEAT crossover rate");
}

//! Novelty search's parameters (evolution.novelty; docs/evolution.md#novelty-search).
void novelty_fields(Studio& s) {
    auto& n = s.draft.evolution.novelty;
    if (field_int("Novelty k", n.k, "", "[1, 1000] nearest behaviours averaged; 15"))
        commit_draft(s, "novelty k");
    if (field_double("Archive threshold", n.archive_threshold, "voxels",
                     "(0, 1e6] novelty to enter the archive at the start; adapts; 1", "%.3g"))
        commit_draft(s, "novelty archive threshold");
    if (field_int("Archive capacity", n.archive_capacity, "", "[0, 100000] oldest leave; 1000"))
        commit_draft(s, "novelty archive capacity");
    if (field_bool("With fitness", n.with_fitness,
                   "fitness as a second objective beside novelty (finds better benders)"))
        commit_draft(s, "novelty with fitness");
}

void evolution_section(Studio& s) {
    auto& ev = s.draft.evolution;
    // One selectable per algorithm, each recorded so a script can pick it ("algorithm neat").
    ImGui::SetNextItemWidth(field_width());
    const bool open = ImGui::BeginCombo(
        "Algorithm", evo::kAlgorithmNames[static_cast<std::size_t>(ev.algorithm)]);
    record_widget(s, "Algorithm");
    if (open) {
        for (std::size_t k = 0; k < evo::kAlgorithmNames.size(); ++k) {
            const auto algorithm = static_cast<evo::Algorithm>(k);
            if (ImGui::Selectable(evo::kAlgorithmNames[k], ev.algorithm == algorithm) &&
                ev.algorithm != algorithm) {
                ev.algorithm = algorithm;
                commit_draft(s, "evolution algorithm");
            }
            record_widget(s, std::string("algorithm ") + evo::kAlgorithmNames[k]);
        }
        ImGui::EndCombo();
    }
    if ((ev.algorithm == evo::Algorithm::Afpo || ev.algorithm == evo::Algorithm::Novelty) &&
        field_double("Crossover rate", ev.crossover_rate, "",
                     "[0, 1]: share of AFPO children made by crossover; 0 = the paper's", "%.3g"))
        commit_draft(s, "AFPO crossover rate");
    if (ev.algorithm == evo::Algorithm::Neat) neat_fields(s);
    if (ev.algorithm == evo::Algorithm::Novelty) novelty_fields(s);
    if (field_int("Population", ev.population, "", "[2, 100000]; paper: 50"))
        commit_draft(s, "population");
    if (field_int("Generations", ev.generations, "", ">= 0; paper: 2000"))
        commit_draft(s, "generations");
    if (field_double("Wall budget", ev.wall_budget_h, "h", "(0, 1e5]; paper: 48 h", "%.4g"))
        commit_draft(s, "wall budget");
    if (field_int("Neutral retries", ev.max_neutral_retries, "",
                  "mutation retries for an identical or invalid child; 1500"))
        commit_draft(s, "neutral retries");
    if (field_u64("Seed", ev.seed, "the run's random seed")) commit_draft(s, "seed");
    if (field_int("Threads", ev.threads, "", "[0, 1024]; 0 = all hardware threads"))
        commit_draft(s, "threads");
    auto& c = ev.cppn;
    if (field_int("CPPN min hidden", c.min_hidden_nodes, "nodes", "paper Table 2: 4"))
        commit_draft(s, "CPPN min hidden nodes");
    if (field_int("CPPN max hidden", c.max_hidden_nodes, "nodes", "paper Table 2: 10"))
        commit_draft(s, "CPPN max hidden nodes");
    if (field_double("Weight range", c.weight_range, "+-", "(0, 100]; paper: 1", "%.3g"))
        commit_draft(s, "CPPN weight range");
    if (field_double("Weight sigma", c.mutation_weight_sigma, "", "(0, 100]; 0.5", "%.3g"))
        commit_draft(s, "CPPN weight sigma");
}

}  // namespace

void draw_experiment_panel(Studio& s) {
    sync_draft(s);
    file_section(s);
    ImGui::Separator();
    if (field_text("##name", s.draft.name, "experiment name")) commit_draft(s, "name");
    if (field_text("##description", s.draft.description, "description: the problem and sources",
                   true))
        commit_draft(s, "description");
    const ImGuiTreeNodeFlags open = ImGuiTreeNodeFlags_DefaultOpen;
    if (ImGui::CollapsingHeader("Workspace", open)) workspace_section(s);
    const bool materials_open = ImGui::CollapsingHeader("Materials");
    record_widget(s, "header Materials");
    if (materials_open) materials_section(s);
    if (ImGui::CollapsingHeader("Actuation and environment")) actuation_section(s);
    if (ImGui::CollapsingHeader("Simulation timing", open)) simulation_section(s);
    if (ImGui::CollapsingHeader("Fitness", open)) fitness_section(s);
    const bool evolution_open = ImGui::CollapsingHeader("Evolution (algorithm, CPPN)");
    record_widget(s, "header Evolution");
    if (evolution_open) evolution_section(s);
}

}  // namespace bhm::app::gui
