// The Analysis tile (bottom right): the population table, every generation's champion (replay
// any, or beside the one shown), the AFPO age-vs-fitness scatter of the population, its
// volume-vs-fitness Pareto plot (issue 44; a click shows that body), time plots of the body
// shown (centre of mass, tip, bend angle) whose cursor is the replay clock, and the robustness
// table of bodies against controllers (panel_robustness.cpp).
#include <array>
#include <cstdio>
#include <string>

#include <imgui.h>

#include "app/gui/actions/studio_actions.hpp"
#include "app/gui/panels/panels.hpp"
#include "app/gui/session/champion_history.hpp"
#include "app/gui/session/pareto_model.hpp"
#include "app/gui/widgets/check_badge.hpp"
#include "app/gui/widgets/mini_plot.hpp"
#include "app/gui/widgets/ui_widgets.hpp"

namespace bhm::app::gui {

namespace {

void champions_tab(Studio& s) {
    // (the flags column: exploit_cell, panels.hpp)
    const std::string dir = s.run.snapshot ? s.run.snapshot->run_dir : "";
    s.run.champion_history.refresh(dir);
    const auto& entries = s.run.champion_history.entries();
    if (entries.empty()) {
        ImGui::TextDisabled(dir.empty() ? "No run: champions appear here as a run finds them."
                                        : "No champion saved yet.");
        return;
    }
    ImGui::BeginDisabled(!s.bodies.compared);
    if (tracked_button(s, "Clear beside")) clear_compared_body(s);
    ImGui::EndDisabled();
    ImGui::SameLine();
    ImGui::TextDisabled("%zu champions; click to replay, 'beside' to compare, 'FEM' to verify",
                        entries.size());
    const ImGuiTableFlags flags = ImGuiTableFlags_ScrollY | ImGuiTableFlags_RowBg |
                                  ImGuiTableFlags_BordersOuter | ImGuiTableFlags_SizingStretchProp;
    // CalculiX in the loop: the badge of each champion whose body was checked (the live run's
    // checks, matched by id; a watched directory's files do not hold them).
    const bool checks = s.run.snapshot && !s.run.snapshot->loop_checks.empty();
    if (!ImGui::BeginTable("champions", 7 + checks, flags, ImGui::GetContentRegionAvail())) return;
    ImGui::TableSetupScrollFreeze(0, 1);
    ImGui::TableSetupColumn("gen");
    ImGui::TableSetupColumn("id");
    ImGui::TableSetupColumn("fitness");
    ImGui::TableSetupColumn("voxels");
    ImGui::TableSetupColumn("flags");
    if (checks) ImGui::TableSetupColumn("CalculiX");
    ImGui::TableSetupColumn("");
    ImGui::TableSetupColumn("");
    ImGui::TableHeadersRow();
    for (auto it = entries.rbegin(); it != entries.rend(); ++it) {  // newest first
        const auto& e = *it;
        ImGui::TableNextRow();
        ImGui::TableNextColumn();
        char label[48];
        std::snprintf(label, sizeof label, "%d##champion", e.generation);
        const bool shown = s.bodies.shown && s.bodies.shown->id == e.id;
        // The whole row replays it (only the "gen" cell did); "beside" overlaps it.
        if (ImGui::Selectable(
                label, shown,
                ImGuiSelectableFlags_SpanAllColumns | ImGuiSelectableFlags_AllowItemOverlap))
            replay_champion(s, e, false);
        record_widget(s, "champion gen " + std::to_string(e.generation));
        ImGui::TableNextColumn();
        ImGui::Text("#%lld", static_cast<long long>(e.id));
        ImGui::TableNextColumn();
        ImGui::TextUnformatted(format_fitness(e.fitness, e.measure).c_str());
        record_widget(s, "champion fitness gen " + std::to_string(e.generation));
        ImGui::TableNextColumn();
        ImGui::Text("%d", e.voxels);
        ImGui::TableNextColumn();
        exploit_cell(s, e.exploits, "champion flags gen " + std::to_string(e.generation));
        if (checks) {
            ImGui::TableNextColumn();
            draw_check_badge(s, loop_check_of(*s.run.snapshot, e.id),
                             "champion check gen " + std::to_string(e.generation));
        }
        ImGui::TableNextColumn();
        ImGui::PushID(e.generation);
        if (ImGui::SmallButton("beside")) replay_champion(s, e, true);
        record_widget(s, "beside gen " + std::to_string(e.generation));
        ImGui::TableNextColumn();
        ImGui::BeginDisabled(s.verify.worker.running());
        if (ImGui::SmallButton("FEM")) verify_champion(s, e);
        ImGui::EndDisabled();
        record_widget(s, "verify gen " + std::to_string(e.generation));
        if (ImGui::IsItemHovered(ImGuiHoveredFlags_AllowWhenDisabled))
            ImGui::SetTooltip("replay it and verify it in FEM (Analysis > FEM)");
        ImGui::PopID();
    }
    ImGui::EndTable();
}

void scatter_tab(Studio& s) {
    if (!s.run.snapshot || s.run.snapshot->population.empty()) {
        ImGui::TextDisabled("The population appears after the first generation.");
        return;
    }
    const auto& run = *s.run.snapshot;
    std::vector<ScatterPoint> points;
    std::vector<std::int64_t> ids;
    for (const auto& m : run.population) {
        if (!m.valid || m.fitness < 0.0) continue;  // invalid or diverged: no fitness to place
        ScatterPoint p;
        p.x = m.age;
        p.y = m.fitness;
        p.color = m.pareto_rank == 0 ? IM_COL32(214, 69, 56, 255) : IM_COL32(110, 120, 135, 220);
        p.radius = m.pareto_rank == 0 ? 4.0f : 3.0f;
        p.ring = run.has_champion && m.id == run.champion.id;
        points.push_back(p);
        ids.push_back(m.id);
    }
    ImGui::TextDisabled("AFPO: age (x) vs fitness (y); red = Pareto front, ring = champion");
    int hovered = -1;
    const auto clicked = draw_scatter_plot(
        "age fitness", points, "age (generations)", fitness_unit(run.experiment.fitness.measure),
        ImGui::GetContentRegionAvail(), &hovered, /*integer_x=*/true);
    record_widget(s, "scatter plot");
    if (hovered >= 0) {
        const auto& p = points[static_cast<std::size_t>(hovered)];
        ImGui::SetTooltip("#%lld\nage %.0f\nfitness %s",
                          static_cast<long long>(ids[static_cast<std::size_t>(hovered)]), p.x,
                          format_fitness(p.y, run.experiment.fitness.measure).c_str());
    }
    if (clicked) select_individual(s, ids[static_cast<std::size_t>(*clicked)]);
}

// Volume (x) against fitness (y) of the population: the volume-vs-fitness front in red, the
// champion ringed; each point is recorded as widget "pareto point #ID" for scripts.
void pareto_tab(Studio& s) {
    if (!s.run.snapshot || s.run.snapshot->population.empty()) {
        ImGui::TextDisabled("The population appears after the first generation.");
        return;
    }
    const auto& run = *s.run.snapshot;
    // A view option, not studio state: kept in ImGui's storage of this window, like a tab's.
    bool* active = ImGui::GetStateStorage()->GetBoolRef(ImGui::GetID("pareto active axis"), false);
    ImGui::Checkbox("active voxels on x", active);
    record_widget(s, "pareto active voxels");
    if (ImGui::IsItemHovered())
        ImGui::SetTooltip(
            "plot active voxels (fitness.minimize_active_voxels, always smaller) "
            "instead of the whole volume");
    const auto entries =
        pareto_entries(run, *active ? ParetoAxis::ActiveVoxels : ParetoAxis::Volume);
    std::vector<ScatterPoint> points;
    int front = 0;
    for (const auto& e : entries) {
        ScatterPoint p;
        p.x = e.voxels;
        p.y = e.fitness;
        p.color = e.on_front ? IM_COL32(214, 69, 56, 255) : IM_COL32(110, 120, 135, 220);
        p.radius = e.on_front ? 4.0f : 3.0f;
        p.ring = e.champion;
        points.push_back(p);
        front += e.on_front;
    }
    const auto objective = run.experiment.fitness.volume_objective;
    const bool larger = !*active && objective == evo::VolumeObjective::Maximize;
    const bool is_objective = *active ? run.experiment.fitness.minimize_active_voxels
                                      : objective != evo::VolumeObjective::Off;
    ImGui::TextDisabled(
        "%d on the front (red; %s %s, %s), ring = champion; click a point to show it", front,
        larger ? "larger" : "smaller", *active ? "active voxels" : "volume",
        is_objective ? "an objective of this run" : "not an objective of this run");
    int hovered = -1;
    std::vector<ImVec2> screen;
    const auto clicked = draw_scatter_plot(
        "volume fitness", points, *active ? "active voxels" : "volume (voxels)",
        fitness_unit(run.experiment.fitness.measure), ImGui::GetContentRegionAvail(), &hovered,
        /*integer_x=*/true, &screen);
    record_widget(s, "pareto plot");
    for (std::size_t k = 0; k < screen.size(); ++k)
        s.ui.widgets["pareto point #" + std::to_string(entries[k].id)] =
            WidgetRect{{screen[k].x - 1.0f, screen[k].y - 1.0f},
                       {screen[k].x + 1.0f, screen[k].y + 1.0f},
                       s.ui.frame};
    if (hovered >= 0) {
        const auto& e = entries[static_cast<std::size_t>(hovered)];
        ImGui::SetTooltip("#%lld%s\n%s %d voxels\nfitness %s", static_cast<long long>(e.id),
                          e.on_front ? " (on the front)" : "", *active ? "active" : "volume",
                          e.voxels,
                          format_fitness(e.fitness, run.experiment.fitness.measure).c_str());
    }
    if (clicked) select_individual(s, entries[static_cast<std::size_t>(*clicked)].id);
}

void time_plots_tab(Studio& s) {
    if (!s.bodies.shown || s.bodies.shown->series.t_s.empty()) {
        ImGui::TextDisabled("Select an individual or a champion: its simulation is plotted here.");
        return;
    }
    const auto& series = s.bodies.shown->series;
    const float each = std::max(
        50.0f, (ImGui::GetContentRegionAvail().y - 2.0f * ImGui::GetStyle().ItemSpacing.y) / 3.0f);
    const float width = ImGui::GetContentRegionAvail().x;
    std::optional<double> seek;
    auto take = [&](std::optional<double> t) {
        if (t) seek = t;
    };
    take(draw_time_plot("com plot", series.t_s,
                        {{&series.com_vox[0], IM_COL32(214, 69, 56, 255), "x"},
                         {&series.com_vox[1], IM_COL32(46, 150, 70, 255), "y"},
                         {&series.com_vox[2], IM_COL32(60, 110, 190, 255), "z"}},
                        s.clock.time_s, "centre of mass", "voxels", ImVec2(width, each)));
    record_widget(s, "time plot com");
    take(draw_time_plot("tip plot", series.t_s, {{&series.tip_vox, IM_COL32(150, 90, 30, 255), ""}},
                        s.clock.time_s, "tip displacement", "voxels", ImVec2(width, each)));
    record_widget(s, "time plot tip");
    take(draw_time_plot("bend plot", series.t_s,
                        {{&series.bend_deg, IM_COL32(120, 60, 160, 255), ""}}, s.clock.time_s,
                        "bend angle", "deg", ImVec2(width, each)));
    record_widget(s, "time plot bend");
    if (seek) {  // scrubbing in a plot moves the replay, as the timeline does
        s.clock.seek(*seek);
        s.clock.playing = false;
    }
}

// A tab of the Analysis tile: its name (the script's "tab <name>", the tooltip) and the shorter
// label it shows when the tile is too narrow for every name.
struct AnalysisTab {
    const char* name;
    const char* short_label;
    void (*draw)(Studio&);
};

float tab_width(const char* label) {
    // ImGui's tab: the label between two frame paddings, and one pixel (TabItemCalcSize).
    return ImGui::CalcTextSize(label, nullptr, true).x + 2.0f * ImGui::GetStyle().FramePadding.x +
           1.0f;
}

// Which tabs show their short label: the widest names give way first, until the row fits. A tab
// bar that does not fit shrinks every tab and cuts their labels ("Populat..."), and one that
// scrolls instead hid Calibrate and FEM at 1280x800 (issue 39): a shorter label keeps every tab
// whole and in reach, and its tooltip says the name.
template <std::size_t N>
std::array<bool, N> short_labels(const AnalysisTab (&tabs)[N], float available) {
    std::array<bool, N> shortened{};
    float row = ImGui::GetStyle().ItemInnerSpacing.x * static_cast<float>(N - 1);
    for (const auto& tab : tabs)
        row += tab_width(tab.name);
    while (row > available) {
        std::size_t widest = N;
        float saved = 0.0f;
        for (std::size_t k = 0; k < N; ++k) {
            const float gain = tab_width(tabs[k].name) - tab_width(tabs[k].short_label);
            if (!shortened[k] && gain > saved) widest = k, saved = gain;
        }
        if (widest == N) break;  // all short and still too wide: ImGui shrinks them
        shortened[widest] = true;
        row -= saved;
    }
    return shortened;
}

}  // namespace

void draw_analysis_panel(Studio& s) {
    static constexpr AnalysisTab tabs[] = {{"Population", "Pop.", draw_population_panel},
                                           {"Champions", "Champs", champions_tab},
                                           {"Age vs fitness", "Ages", scatter_tab},
                                           {"Volume vs fitness", "Vol.", pareto_tab},
                                           {"Time plots", "Plots", time_plots_tab},
                                           {"Calibrate", "Calib.", draw_calibrate_panel},
                                           {"FEM", "FEM", draw_verify_panel},
                                           {"Robustness", "Rob.", draw_robustness_panel}};
    const auto shortened = short_labels(tabs, ImGui::GetContentRegionAvail().x);
    if (!ImGui::BeginTabBar("analysis tabs")) return;
    for (std::size_t k = 0; k < std::size(tabs); ++k) {
        const auto& tab = tabs[k];
        // "###name": the tab keeps its identity (and stays selected) whichever label it shows.
        const std::string label =
            std::string(shortened[k] ? tab.short_label : tab.name) + "###" + tab.name;
        const bool open = ImGui::BeginTabItem(label.c_str());
        record_widget(s, std::string("tab ") + tab.name);
        if (shortened[k] && ImGui::IsItemHovered()) ImGui::SetTooltip("%s", tab.name);
        if (open) {
            tab.draw(s);
            ImGui::EndTabItem();
        }
    }
    ImGui::EndTabBar();
}

}  // namespace bhm::app::gui
