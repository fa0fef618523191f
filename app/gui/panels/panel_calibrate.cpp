// The Calibrate tab (Analysis, docs/studio.md): a measured track (docs/track-format.md) onto the
// body shown, the parameters to fit, the calibration's progress with Cancel, its report, Apply,
// and per tracked point and axis the measured displacement against the simulated one, the red
// cursor on the replay clock (click or drag to scrub).
#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <string>
#include <vector>

#include <imgui.h>

#include "app/gui/actions/calibration_actions.hpp"
#include "app/gui/actions/studio_actions.hpp"
#include "app/gui/panels/file_dialog_widget.hpp"
#include "app/gui/panels/panels.hpp"
#include "app/gui/widgets/mini_plot.hpp"
#include "app/gui/widgets/ui_widgets.hpp"

namespace bhm::app::gui {

namespace {

constexpr ImU32 kMeasured = IM_COL32(20, 20, 20, 255);
constexpr ImU32 kBefore = IM_COL32(237, 125, 33, 255);
constexpr ImU32 kAfter = IM_COL32(60, 110, 190, 255);
constexpr ImU32 kWarning = IM_COL32(190, 60, 30, 255);

void path_field(Studio& s, const char* id, const char* hint, std::string& value) {
    char buffer[1024];
    std::snprintf(buffer, sizeof buffer, "%s", value.c_str());
    // Room for two buttons: the action and the file dialog's.
    const ImGuiStyle& style = ImGui::GetStyle();
    ImGui::SetNextItemWidth(-ImGui::CalcTextSize("Load trackTrack...").x -
                            4.0f * style.FramePadding.x - 2.0f * style.ItemSpacing.x);
    if (ImGui::InputTextWithHint(id, hint, buffer, sizeof buffer)) value = buffer;
    record_widget(s, id + 2);
}

void track_controls(Studio& s) {
    auto& c = s.calibration;
    const bool running = c.session.running();
    path_field(s, "##body file", "BODY.json (optional: show a body file)", c.body_field);
    ImGui::SameLine();
    if (tracked_button(s, "Show body")) show_body_file(s, c.body_field);
    ImGui::SameLine();
    if (tracked_button(s, "Body...")) show_file_dialog(s, FileDialogPurpose::ShowBody);
    if (ImGui::IsItemHovered()) ImGui::SetTooltip("browse for a body file (*.json) to show");
    path_field(s, "##track file", "TRACK.csv (docs/track-format.md)", c.track_field);
    ImGui::SameLine();
    ImGui::BeginDisabled(running || !s.bodies.shown);
    if (tracked_button(s, "Load track")) load_track(s, c.track_field);
    ImGui::SameLine();
    if (tracked_button(s, "Track...")) show_file_dialog(s, FileDialogPurpose::LoadTrack);
    ImGui::EndDisabled();
    if (ImGui::IsItemHovered(ImGuiHoveredFlags_AllowWhenDisabled))
        ImGui::SetTooltip("browse for a measured track (*.csv, docs/track-format.md)");
    if (!c.track) {
        ImGui::TextDisabled(s.bodies.shown ? "Load a track onto %s." : "Show a body first.",
                            s.bodies.shown ? s.bodies.shown->label.c_str() : "");
        return;
    }
    std::string points;
    for (const auto& p : c.track->points) {
        points += (points.empty() ? "" : ", ") + p.name + " (";
        for (int a = 0; a < 3; ++a)
            if (p.axes[static_cast<std::size_t>(a)]) points += "xyz"[a];
        points += ")";
    }
    ImGui::TextWrapped("%s: %zu rows, %.3g to %.3g s; %s; on %s", c.track_path.c_str(),
                       c.track->t_s.size(), c.track->t_s.front(), c.track->t_s.back(),
                       points.c_str(), c.body_label.c_str());
    if (!c.track_warning.empty())
        ImGui::TextColored(ImColor(kWarning), "Warning: %s", c.track_warning.c_str());
    if (s.bodies.shown && s.bodies.shown->framed_body != c.framed_body)
        ImGui::TextColored(ImColor(kWarning), "The body shown is not the track's: no overlay.");
}

void fit_controls(Studio& s) {
    auto& c = s.calibration;
    const bool running = c.session.running();
    ImGui::BeginDisabled(running);
    ImGui::TextUnformatted("Fit:");
    for (std::size_t i = 0; i < c.fit_names.size(); ++i) {
        // A muscle experiment has no sine amplitude, a sine one no twitch times.
        if (!fit_name_applies(c.fit_names[i], c.experiment)) continue;
        ImGui::SameLine();
        if (ImGui::GetContentRegionAvail().x < ImGui::CalcTextSize(c.fit_names[i].c_str()).x + 30.0f)
            ImGui::NewLine();
        bool on = c.fit_on[i];
        if (ImGui::Checkbox(c.fit_names[i].c_str(), &on)) c.fit_on[i] = on;
        record_widget(s, "fit " + c.fit_names[i]);
    }
    ImGui::SetNextItemWidth(ImGui::GetFontSize() * 6.0f);
    ImGui::InputInt("simulations at most", &c.max_simulations, 10, 50);
    record_widget(s, "calibration budget");
    ImGui::SameLine();
    ImGui::SetNextItemWidth(ImGui::GetFontSize() * 5.0f);
    ImGui::InputInt("threads (0: all)", &c.threads, 1, 1);
    c.threads = std::max(0, c.threads);
    ImGui::EndDisabled();
    ImGui::BeginDisabled(running || !c.track);
    if (tracked_button(s, "Calibrate")) start_calibration(s);
    ImGui::EndDisabled();
    ImGui::SameLine();
    ImGui::BeginDisabled(!running);
    if (tracked_button(s, "Cancel calibration")) cancel_calibration(s);
    ImGui::EndDisabled();
}

void progress_line(Studio& s) {
    const auto& snap = s.calibration.snapshot;
    if (!snap || snap->track != s.calibration.track) return;
    double elapsed = snap->elapsed_s;
    if (snap->phase == CalibrationPhase::Running)
        elapsed = std::chrono::duration<double>(std::chrono::steady_clock::now() - snap->started)
                      .count();
    char text[160];
    if (!snap->fitting) {
        if (snap->phase != CalibrationPhase::Running) return;
        std::snprintf(text, sizeof text, "simulating the body at the track's times, %s",
                      format_duration(elapsed).c_str());
        ImGui::ProgressBar(0.0f, ImVec2(-1.0f, 0.0f), text);
    } else {
        const bool converged = !snap->result || snap->result->converged;
        const char* state = snap->phase == CalibrationPhase::Running     ? ""
                            : snap->phase == CalibrationPhase::Cancelled ? " (cancelled)"
                            : snap->phase == CalibrationPhase::Failed    ? " (failed)"
                            : converged                                  ? " (done)"
                                                : " (budget reached: not converged)";
        char best[32] = "-";
        if (std::isfinite(snap->best_misfit_m))
            std::snprintf(best, sizeof best, "%.4g mm", snap->best_misfit_m * 1e3);
        std::snprintf(text, sizeof text, "%d / %d simulations, best %s, %s%s",
                      snap->simulations, snap->budget, best, format_duration(elapsed).c_str(),
                      state);
        ImGui::ProgressBar(snap->budget > 0 ? float(snap->simulations) / float(snap->budget) : 0.0f,
                           ImVec2(-1.0f, 0.0f), text);
    }
    record_widget(s, "calibration progress");
    if (snap->phase == CalibrationPhase::Failed)
        ImGui::TextColored(ImColor(kWarning), "%s", snap->error.c_str());
}

void report(Studio& s) {
    const auto& snap = s.calibration.snapshot;
    if (!snap || !snap->result || snap->track != s.calibration.track) return;
    const auto& r = *snap->result;
    const ImGuiTableFlags flags = ImGuiTableFlags_RowBg | ImGuiTableFlags_BordersOuter |
                                  ImGuiTableFlags_SizingStretchProp;
    if (ImGui::BeginTable("calibration report", 5, flags)) {
        for (const char* h : {"parameter", "was", "fitted", "sigma", "unit"})
            ImGui::TableSetupColumn(h);
        ImGui::TableHeadersRow();
        for (const auto& f : r.fitted) {
            ImGui::TableNextRow();
            ImGui::TableNextColumn();
            ImGui::TextUnformatted(f.parameter.name.c_str());
            ImGui::TableNextColumn();
            ImGui::Text("%.4g", f.initial_value);
            ImGui::TableNextColumn();
            ImGui::Text(f.at_bound ? "%.4g (bound)" : "%.4g", f.value);
            ImGui::TableNextColumn();
            if (!r.converged) {
                // The curvature where the budget stopped the search says nothing of how far
                // the optimum is: no number that would pass for an uncertainty.
                ImGui::TextColored(ImColor(kWarning), "not converged");
                if (ImGui::IsItemHovered())
                    ImGui::SetTooltip("%.2g from the curvature at this point, which understates "
                                      "the error of a fit that did not converge",
                                      f.sigma);
            } else if (std::isfinite(f.sigma))
                ImGui::Text("%.2g (%.1f %%)", f.sigma,
                            f.value != 0.0 ? 100.0 * f.sigma / std::abs(f.value) : 0.0);
            else
                ImGui::TextUnformatted("-");
            ImGui::TableNextColumn();
            ImGui::TextUnformatted(evo::fit_unit(f.parameter));
        }
        ImGui::EndTable();
    }
    record_widget(s, "calibration report");
    ImGui::Text("misfit %.4g mm -> %.4g mm (track motion %.4g mm), %d simulations, %s",
                r.misfit_before_m * 1e3, r.misfit_after_m * 1e3, r.motion_rms_m * 1e3,
                r.optimiser_simulations + r.jacobian_simulations + 2,
                format_duration(r.wall_s).c_str());
    if (r.polish_simulations > 0)
        ImGui::Text("Gauss-Newton polish: %d step%s, misfit %.4g mm -> %.4g mm (%s)",
                    r.polish_steps, r.polish_steps == 1 ? "" : "s", r.misfit_before_polish_m * 1e3,
                    r.misfit_after_m * 1e3, r.polish_stop.c_str());
    for (const auto& w : r.warnings) ImGui::TextColored(ImColor(kWarning), "%s", w.c_str());
    const bool applied = s.calibration.applied_job == snap->job;
    ImGui::BeginDisabled(applied);
    if (tracked_button(s, applied ? "Applied" : "Apply to experiment")) apply_calibration(s);
    ImGui::EndDisabled();
    if (ImGui::IsItemHovered(ImGuiHoveredFlags_AllowWhenDisabled))
        ImGui::SetTooltip("Writes the fitted values into the experiment being edited as one "
                          "undoable edit (Ctrl+Z reverts it)");
    if (!run_is_live(s.run.evolution.phase())) return;
    const bool sent = s.calibration.applied_run_job == snap->job;
    ImGui::SameLine();
    ImGui::BeginDisabled(sent);
    if (tracked_button(s, sent ? "Applied to the live run" : "Apply to the live run"))
        apply_calibration_to_run(s);
    ImGui::EndDisabled();
    if (ImGui::IsItemHovered(ImGuiHoveredFlags_AllowWhenDisabled))
        ImGui::SetTooltip("Changes the live run's physics to the fitted values from the next "
                          "generation (a rule change: every member is simulated again under "
                          "them, and the Fitness plot marks the generation)");
}

void plots(Studio& s) {
    const auto& c = s.calibration;
    const auto& snap = c.snapshot;
    if (!c.track || !snap || !snap->preview || snap->track != c.track) return;
    const auto& track = *c.track;
    const auto* after = snap->result ? &snap->result->after : nullptr;
    int count = 0;
    for (const auto& p : track.points)
        for (bool on : p.axes) count += on ? 1 : 0;
    const float each = std::max(
        90.0f, (ImGui::GetContentRegionAvail().y - float(count) * ImGui::GetStyle().ItemSpacing.y) /
                   float(std::max(1, count)));
    std::optional<double> seek;
    const std::size_t rows = track.t_s.size();
    for (std::size_t i = 0; i < track.points.size(); ++i)
        for (std::size_t a = 0; a < 3; ++a) {
            if (!track.points[i].axes[a]) continue;
            // Displacements from the first row in mm, as the misfit compares them.
            auto displacement = [&](const std::vector<std::array<double, 3>>& v) {
                std::vector<double> d;
                if (v.size() < rows) return d;  // a diverged simulation: no curve
                for (std::size_t k = 0; k < rows; ++k) d.push_back((v[k][a] - v[0][a]) * 1e3);
                return d;
            };
            const auto measured = displacement(track.points[i].position_m);
            const auto before = displacement(snap->preview->position_m[i]);
            const auto fitted =
                after ? displacement(after->position_m[i]) : std::vector<double>();
            std::vector<PlotCurve> curves = {{&measured, kMeasured, "measured", true},
                                             {&before, kBefore, "simulated", false}};
            if (after) curves.push_back({&fitted, kAfter, "calibrated", false});
            const std::string title = track.points[i].name + "." + "xyz"[a];
            const std::string id = "track plot " + title;
            if (auto t = draw_time_plot(id.c_str(), track.t_s, curves, s.clock.time_s,
                                        title.c_str(), "mm",
                                        ImVec2(ImGui::GetContentRegionAvail().x, each)))
                seek = t;
            record_widget(s, id);
        }
    if (seek) {
        s.clock.seek(*seek);
        s.clock.playing = false;
    }
}

}  // namespace

void draw_calibrate_panel(Studio& s) {
    // One scrolling region: in a short tile the report and the plots stay reachable.
    ImGui::BeginChild("calibrate scroll", ImVec2(0.0f, 0.0f), false);
    track_controls(s);
    fit_controls(s);
    progress_line(s);
    report(s);
    plots(s);
    ImGui::EndChild();
}

}  // namespace bhm::app::gui
