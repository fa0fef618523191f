// Analysis > Robustness (issue 44): pick bodies (the shown run's champions, body files) and
// controllers (as `bhm robustness --controllers`), evaluate the table on worker threads with
// progress and Cancel, then the table and its heatmap (the CLI's colours, drawn with ImDrawList);
// a click on a cell shows that body driven by that controller; CSV and PNG exported as the CLI
// writes them. Widgets recorded for scripts: "Run robustness", "Cancel robustness", "robustness
// champion gen N", "robustness cell B,C" (row B, column C from 0), "Export robustness CSV",
// "Export robustness PNG".
#include <algorithm>
#include <cstdio>
#include <string>

#include <imgui.h>

#include "app/cli/robustness_plot.hpp"
#include "app/gui/actions/robustness_actions.hpp"
#include "app/gui/panels/panels.hpp"
#include "app/gui/widgets/ui_widgets.hpp"

namespace bhm::app::gui {

namespace {

ImU32 im_color(const Rgb& c) {
    return IM_COL32(c[0], c[1], c[2], 255);
}

// The shown run's champions as ticks (newest first), in a child of a few lines.
void champion_picks(Studio& s) {
    const std::string dir = s.run.snapshot ? s.run.snapshot->run_dir : "";
    s.run.champion_history.refresh(dir);
    const auto& entries = s.run.champion_history.entries();
    if (entries.empty()) {
        ImGui::TextDisabled("Champions: none shown (start or open a run to pick its champions).");
        return;
    }
    ImGui::TextDisabled("Champions of the shown run (%zu):", entries.size());
    ImGui::SameLine();
    if (ImGui::SmallButton("all")) {
        for (const auto& e : entries)
            s.robustness.champions.insert(e.generation);
    }
    ImGui::SameLine();
    if (ImGui::SmallButton("none")) s.robustness.champions.clear();
    const float lines = static_cast<float>(std::min<std::size_t>(entries.size(), 4));
    ImGui::BeginChild("robustness champions", ImVec2(0, lines * ImGui::GetFrameHeightWithSpacing()),
                      false);
    for (auto it = entries.rbegin(); it != entries.rend(); ++it) {
        bool picked = s.robustness.champions.count(it->generation) > 0;
        char label[96];
        std::snprintf(label, sizeof label, "gen %d  #%lld  %s", it->generation,
                      static_cast<long long>(it->id),
                      format_fitness(it->fitness, it->measure).c_str());
        if (ImGui::Checkbox(label, &picked)) {
            if (picked)
                s.robustness.champions.insert(it->generation);
            else
                s.robustness.champions.erase(it->generation);
        }
        record_widget(s, "robustness champion gen " + std::to_string(it->generation));
    }
    ImGui::EndChild();
}

void progress_row(Studio& s) {
    const auto& st = s.robustness.state;
    if (s.robustness.runner.running()) {
        const int done = st ? st->done : 0, total = st ? std::max(1, st->total) : 1;
        char overlay[64];
        std::snprintf(overlay, sizeof overlay, "%d / %d evaluated", done, total);
        ImGui::ProgressBar(static_cast<float>(done) / static_cast<float>(total),
                           ImVec2(-ImGui::GetFontSize() * 6.0f, 0.0f), overlay);
        ImGui::SameLine();
        if (tracked_button(s, "Cancel robustness")) cancel_robustness(s);
        return;
    }
    if (tracked_button(s, "Run robustness")) start_robustness(s);
    ImGui::SameLine();
    if (!st) {
        ImGui::TextDisabled("each cell a full evaluation under %s's fitness",
                            robustness_experiment(s).name.c_str());
    } else if (st->phase == RobustnessPhase::Failed) {
        ImGui::TextColored(ImVec4(0.75f, 0.15f, 0.1f, 1.0f), "%s", st->error.c_str());
    } else if (st->phase == RobustnessPhase::Cancelled) {
        ImGui::TextDisabled("cancelled after %d of %d evaluations", st->done, st->total);
    } else {
        ImGui::TextDisabled("%d evaluations in %.1f s under %s", st->total, st->elapsed_s,
                            st->request->experiment.name.c_str());
    }
}

// The heatmap: rows bodies, columns controllers, the CLI's colours; each cell a button.
void heatmap(Studio& s, const evo::RobustnessTable& table, evo::FitnessMeasure measure) {
    const HeatmapScale scale = robustness_scale(table);
    const std::size_t rows = table.bodies.size(), cols = table.controllers.size();
    const float label_w = ImGui::GetFontSize() * 9.0f;
    const float avail = ImGui::GetContentRegionAvail().x - label_w;
    const float cell = std::clamp(avail / static_cast<float>(std::max<std::size_t>(cols, 1)),
                                  ImGui::GetFontSize() * 1.5f, ImGui::GetFontSize() * 4.0f);
    ImDrawList* draw = ImGui::GetWindowDrawList();
    const ImVec2 origin = ImGui::GetCursorScreenPos();
    for (std::size_t b = 0; b < rows; ++b) {
        const float y = origin.y + static_cast<float>(b) * cell;
        const std::string& name = table.bodies[b];
        draw->PushClipRect(ImVec2(origin.x, y), ImVec2(origin.x + label_w - 4.0f, y + cell), true);
        draw->AddText(ImVec2(origin.x, y + 0.5f * (cell - ImGui::GetFontSize())),
                      ImGui::GetColorU32(ImGuiCol_Text), name.c_str());
        draw->PopClipRect();
        for (std::size_t c = 0; c < cols; ++c) {
            const ImVec2 a(origin.x + label_w + static_cast<float>(c) * cell, y);
            const ImVec2 z(a.x + cell - 1.0f, a.y + cell - 1.0f);
            const double f = table.at(b, c);
            draw->AddRectFilled(a, z, im_color(robustness_color(f, scale)));
            if (!robustness_cell_valid(f)) {
                draw->AddLine(ImVec2(a.x + 3, a.y + 3), ImVec2(z.x - 3, z.y - 3),
                              IM_COL32(60, 60, 60, 255));
                draw->AddLine(ImVec2(z.x - 3, a.y + 3), ImVec2(a.x + 3, z.y - 3),
                              IM_COL32(60, 60, 60, 255));
            }
            if (static_cast<int>(b) == s.robustness.shown_body &&
                static_cast<int>(c) == s.robustness.shown_controller)
                draw->AddRect(a, z, IM_COL32(214, 69, 56, 255), 0.0f, 0, 2.5f);
            ImGui::SetCursorScreenPos(a);
            const std::string id = std::to_string(b) + "," + std::to_string(c);
            if (area_button(("##robustness cell " + id).c_str(), ImVec2(cell - 1.0f, cell - 1.0f)))
                show_robustness_cell(s, b, c);
            record_widget(s, "robustness cell " + id);
            if (ImGui::IsItemHovered())
                ImGui::SetTooltip("%s\ndriven by %s\nfitness %s\nclick to show it", name.c_str(),
                                  table.controllers[c].c_str(),
                                  f == evo::kDivergedFitness  ? "diverged"
                                  : f == evo::kInvalidFitness ? "rejected (reject_* constraint)"
                                                              : format_fitness(f, measure).c_str());
        }
    }
    ImGui::SetCursorScreenPos(ImVec2(origin.x, origin.y + static_cast<float>(rows) * cell + 4.0f));
    ImGui::TextDisabled("dark blue %s .. yellow %s; grey crossed: diverged or rejected",
                        format_fitness(scale.lo, measure).c_str(),
                        format_fitness(scale.hi, measure).c_str());
}

// The numbers: one row per body, one column per controller.
void number_table(const evo::RobustnessTable& table, evo::FitnessMeasure measure) {
    const int cols = static_cast<int>(table.controllers.size());
    const ImGuiTableFlags flags =
        ImGuiTableFlags_RowBg | ImGuiTableFlags_BordersOuter | ImGuiTableFlags_SizingStretchProp;
    if (cols + 1 > 64 || !ImGui::BeginTable("robustness numbers", cols + 1, flags)) return;
    ImGui::TableSetupColumn("body");
    for (const auto& c : table.controllers)
        ImGui::TableSetupColumn(c.c_str());
    ImGui::TableHeadersRow();
    for (std::size_t b = 0; b < table.bodies.size(); ++b) {
        ImGui::TableNextRow();
        ImGui::TableNextColumn();
        ImGui::TextUnformatted(table.bodies[b].c_str());
        for (std::size_t c = 0; c < table.controllers.size(); ++c) {
            ImGui::TableNextColumn();
            const double f = table.at(b, c);
            ImGui::TextUnformatted(f == evo::kDivergedFitness ? "diverged"
                                   : f == evo::kInvalidFitness
                                       ? "rejected"
                                       : format_fitness(f, measure).c_str());
        }
    }
    ImGui::EndTable();
}

}  // namespace

void draw_robustness_panel(Studio& s) {
    auto& r = s.robustness;
    // Run first and the table right under it: in a short Analysis tile the heatmap is in view
    // without scrolling past the picks, which follow it.
    progress_row(s);
    const evo::RobustnessTable* table = robustness_table(s);
    const auto measure = table ? r.state->request->experiment.fitness.measure
                               : robustness_experiment(s).fitness.measure;
    if (table) heatmap(s, *table, measure);
    section_title("Bodies (rows)");
    champion_picks(s);
    hinted_text_field(s, "##robustness body files", "body files, comma-separated (a.json,b.json)",
                      r.body_files);
    section_title("Controllers (columns)");
    hinted_text_field(s, "##robustness controllers",
                      "uniform, wave, random, random:SEED, controller.json, a run folder",
                      r.controllers);
    if (!table) return;
    section_title("Table (click a heatmap cell to show that body with that controller)");
    number_table(*table, measure);
    section_title("Export (as bhm robustness writes them)");
    hinted_text_field(s, "##robustness csv path", "robustness.csv", r.csv_path);
    if (tracked_button(s, "Export robustness CSV")) export_robustness_csv(s, r.csv_path);
    hinted_text_field(s, "##robustness png path", "robustness.png", r.png_path);
    if (tracked_button(s, "Export robustness PNG")) export_robustness_png(s, r.png_path);
}

}  // namespace bhm::app::gui
