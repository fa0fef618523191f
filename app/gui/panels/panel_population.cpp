// The Fitness panel (the plot) and the Population panel: the current population with the Pareto
// front marked and, in runs with CalculiX in the loop, each checked body's badge; a click on a
// row simulates that individual for the 3D view, its "FEM" button verifies it (Analysis > FEM).
#include <algorithm>
#include <cstdio>

#include <imgui.h>

#include "app/gui/actions/studio_actions.hpp"
#include "app/gui/panels/panels.hpp"
#include "app/gui/widgets/check_badge.hpp"
#include "app/gui/widgets/fitness_plot.hpp"
#include "app/gui/widgets/ui_widgets.hpp"

namespace bhm::app::gui {

void draw_fitness_panel(Studio& s) {
    // One plot per measure: after a change of rules, values in voxels and in degrees never share
    // a line or an axis. Other runs (Compare) are overlaid thin on the plot of the same measure.
    std::vector<MeasureSeries> plots;
    if (s.run.snapshot && !s.run.snapshot->history.empty())
        plots = split_by_measure(*s.run.snapshot);
    std::vector<std::vector<OverlayCurve>> overlays(plots.size());
    for (const auto& other : s.run.compared) {
        if (!other.snapshot) continue;
        for (auto& series : split_by_measure(*other.snapshot)) {
            auto it = std::find_if(plots.begin(), plots.end(), [&](const MeasureSeries& m) {
                return m.measure == series.measure;
            });
            if (it == plots.end()) {
                plots.push_back({series.measure, {}});
                overlays.emplace_back();
                it = plots.end() - 1;
            }
            overlays[static_cast<std::size_t>(it - plots.begin())].push_back(
                {other.label, std::move(series.records)});
        }
    }
    if (plots.empty()) {
        // Before a run has history, label the axis with the measure the next run will use.
        plots.push_back({s.run.snapshot && s.run.snapshot->loaded
                             ? s.run.snapshot->experiment.fitness.measure
                             : s.document.experiment().fitness.measure,
                         {}});
        overlays.emplace_back();
    }
    const std::vector<RuleChangeNote> no_changes;
    const auto& changes = s.run.snapshot ? s.run.snapshot->rule_changes : no_changes;
    const float line = ImGui::GetTextLineHeightWithSpacing();
    const float min_height = ImGui::GetFontSize() * kMinPlotFonts;
    const float avail = ImGui::GetContentRegionAvail().y;
    const float each = (avail - line * plots.size()) / plots.size();
    s.run.fitness_plot_overlays = 0;
    for (const auto& o : overlays)
        s.run.fitness_plot_overlays += static_cast<int>(o.size());
    auto draw_plot = [&](std::size_t k, float height) {
        const auto measure = plots[k].measure;
        const char* name = evo::kFitnessNames[static_cast<std::size_t>(measure)];
        const float width = ImGui::GetContentRegionAvail().x;
        s.run.fitness_plot.draw(plots[k].records, changes, ImVec2(width, height),
                                fitness_unit(measure), overlays[k]);
        record_widget(s, std::string("fitness plot ") + name);
    };
    // Stacked while each keeps its minimum height (at most two); else one tab per measure, the
    // newest measure's selected when it appears.
    const bool tabs = plots.size() > 2 || (plots.size() > 1 && each < min_height);
    const bool new_measure = plots.size() != s.run.fitness_plot.measures_seen;
    s.run.fitness_plot.measures_seen = plots.size();
    if (tabs) {
        if (ImGui::BeginTabBar("measures")) {
            for (std::size_t k = 0; k < plots.size(); ++k) {
                const auto measure = plots[k].measure;
                const char* name = evo::kFitnessNames[static_cast<std::size_t>(measure)];
                const std::string label = std::string(name) + " (" + fitness_unit(measure) + ")";
                const ImGuiTabItemFlags flags =
                    new_measure && k + 1 == plots.size() ? ImGuiTabItemFlags_SetSelected : 0;
                const bool open = ImGui::BeginTabItem(label.c_str(), nullptr, flags);
                record_widget(s, std::string("fitness tab ") + name);
                if (open) {
                    draw_plot(k, std::max(min_height, ImGui::GetContentRegionAvail().y));
                    ImGui::EndTabItem();
                }
            }
            ImGui::EndTabBar();
        }
        return;
    }
    for (std::size_t k = 0; k < plots.size(); ++k) {
        const auto measure = plots[k].measure;
        ImGui::PushID(static_cast<int>(measure));
        ImGui::TextDisabled("%s (%s)", evo::kFitnessNames[static_cast<std::size_t>(measure)],
                            fitness_unit(measure));
        draw_plot(k, std::max(min_height, each));
        ImGui::PopID();
    }
}

void exploit_cell(Studio& s, const evo::ExploitReport& report, const std::string& widget) {
    const std::string letters = exploit_letters(report);
    if (letters.empty()) {
        ImGui::TextDisabled(report.checked ? "-" : "?");
        if (!report.checked && ImGui::IsItemHovered())
            ImGui::SetTooltip("evaluated before exploit detection");
        return;
    }
    ImGui::TextColored(ImVec4(0.80f, 0.15f, 0.10f, 1.0f), "%s", letters.c_str());
    record_widget(s, widget);
    if (ImGui::IsItemHovered()) ImGui::SetTooltip("%s", exploit_summary(report).c_str());
}

void draw_population_panel(Studio& s) {
    if (!s.run.snapshot || s.run.snapshot->population.empty()) {
        ImGui::TextDisabled("The population appears after the first generation.");
        return;
    }
    const auto& run = *s.run.snapshot;
    const auto measure = run.experiment.fitness.measure;
    ImGui::BeginDisabled(s.bodies.follow_champion);
    if (tracked_button(s, "Follow champion")) follow_champion(s);
    ImGui::EndDisabled();
    ImGui::SameLine();
    // NEAT has species instead of a Pareto front: that column shows each member's species.
    const bool neat = evo::uses_neat(run.experiment.evolution.algorithm);
    int front = 0;
    for (const auto& m : run.population)
        front += m.pareto_rank == 0;
    if (neat)
        ImGui::TextDisabled("%zu individuals in %d species", run.population.size(), run.species);
    else
        ImGui::TextDisabled("%zu individuals, %d on the Pareto front (*)", run.population.size(),
                            front);
    const ImGuiTableFlags flags = ImGuiTableFlags_ScrollY | ImGuiTableFlags_RowBg |
                                  ImGuiTableFlags_BordersOuter | ImGuiTableFlags_SizingStretchProp;
    // Novelty search selects on novelty: its members show it beside their fitness.
    const bool novelty = run.experiment.evolution.algorithm == evo::Algorithm::Novelty;
    // CalculiX in the loop: a column of badges, only in runs that check (or have checked).
    const bool checks = run.experiment.evolution.verify.enabled() || !run.loop_checks.empty();
    if (!ImGui::BeginTable("population", 8 + novelty + checks, flags,
                           ImGui::GetContentRegionAvail()))
        return;
    ImGui::TableSetupScrollFreeze(0, 1);
    ImGui::TableSetupColumn("id");
    ImGui::TableSetupColumn(measure == evo::FitnessMeasure::BendAngleDeg ? "fitness (deg)"
                                                                         : "fitness (vox)");
    if (novelty) ImGui::TableSetupColumn("novelty");
    ImGui::TableSetupColumn("age");
    ImGui::TableSetupColumn("voxels");
    ImGui::TableSetupColumn("active");
    ImGui::TableSetupColumn(neat ? "species" : "front");
    ImGui::TableSetupColumn("flags");
    if (checks) ImGui::TableSetupColumn("CalculiX");
    ImGui::TableSetupColumn("");
    ImGui::TableHeadersRow();
    for (const auto& m : run.population) {
        ImGui::TableNextRow();
        ImGui::TableNextColumn();
        char id[48];
        std::snprintf(id, sizeof id, "#%lld", static_cast<long long>(m.id));
        const bool selected = s.bodies.shown && s.bodies.shown->id == m.id;
        // The row shows it; the "FEM" button at its end (drawn over the row) verifies it.
        if (ImGui::Selectable(
                id, selected,
                ImGuiSelectableFlags_SpanAllColumns | ImGuiSelectableFlags_AllowItemOverlap))
            select_individual(s, m.id);
        record_widget(s, std::string("individual ") + id);
        ImGui::TableNextColumn();
        if (!m.valid)
            ImGui::TextDisabled("invalid");
        else if (m.fitness < 0.0)
            ImGui::TextDisabled("diverged");
        else
            ImGui::Text("%.3f", m.fitness);
        if (novelty) {
            ImGui::TableNextColumn();
            if (m.novelty >= 0.0)
                ImGui::Text("%.3f", m.novelty);
            else
                ImGui::TextDisabled("-");
            record_widget(s, std::string("novelty ") + id);
        }
        ImGui::TableNextColumn();
        ImGui::Text("%d", m.age);
        ImGui::TableNextColumn();
        ImGui::Text("%d", m.voxels);
        ImGui::TableNextColumn();
        ImGui::Text("%.0f %%", 100.0 * m.active_fraction());
        ImGui::TableNextColumn();
        if (neat)
            ImGui::Text("%d", m.species);
        else
            ImGui::TextUnformatted(m.pareto_rank == 0 ? "*" : "");
        ImGui::TableNextColumn();
        exploit_cell(s, m.exploits, std::string("flags ") + id);
        if (checks) {
            ImGui::TableNextColumn();
            draw_check_badge(s, loop_check_of(run, m.id), std::string("check ") + id);
        }
        ImGui::TableNextColumn();
        ImGui::PushID(id);
        ImGui::BeginDisabled(s.verify.worker.running() || !m.body);
        if (ImGui::SmallButton("FEM")) verify_individual(s, m.id);
        ImGui::EndDisabled();
        record_widget(s, std::string("verify ") + id);
        if (ImGui::IsItemHovered(ImGuiHoveredFlags_AllowWhenDisabled))
            ImGui::SetTooltip("show it and verify it in FEM (Analysis > FEM)");
        ImGui::PopID();
    }
    ImGui::EndTable();
}

}  // namespace bhm::app::gui
