// The Replay panel: a timeline over the whole simulated time with the settle phase shaded,
// play / pause, frame steps, speed, loop and scrubbing (click or drag on the timeline).
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <string>

#include <imgui.h>

#include "app/gui/actions/studio_actions.hpp"
#include "app/gui/panels/panels.hpp"
#include "app/gui/widgets/plot_axes.hpp"
#include "app/gui/widgets/ui_widgets.hpp"

namespace bhm::app::gui {

namespace {

void timeline(Studio& s, float height) {
    auto& clock = s.clock;
    const double settle = s.bodies.shown ? s.bodies.shown->experiment.simulation.settle_s : 0.0;
    const double duration = std::max(clock.duration_s, 1e-9);
    ImDrawList* dl = ImGui::GetWindowDrawList();
    const ImVec2 origin = ImGui::GetCursorScreenPos();
    const float width = ImGui::GetContentRegionAvail().x;
    area_button("timeline", ImVec2(width, height));
    record_widget(s, "timeline");
    const float pad = ImGui::GetFontSize() * 0.5f;
    const ImVec2 lo{origin.x + pad, origin.y + 2.0f};
    const ImVec2 hi{origin.x + width - pad, origin.y + height - ImGui::GetFontSize() - 4.0f};
    auto x_of = [&](double t) { return lo.x + float(t / duration) * (hi.x - lo.x); };

    if (ImGui::IsItemActive() && s.bodies.shown) {  // click or drag: scrub
        const float mx = std::clamp(ImGui::GetIO().MousePos.x, lo.x, hi.x);
        clock.seek((mx - lo.x) / (hi.x - lo.x) * duration);
        clock.playing = false;
    }
    dl->AddRectFilled(lo, hi, IM_COL32(246, 247, 249, 255));
    if (s.bodies.shown && settle > 0.0) {
        dl->AddRectFilled(lo, {x_of(std::min(settle, duration)), hi.y},
                          IM_COL32(150, 160, 175, 90));
        dl->AddText({lo.x + 4.0f, lo.y + 1.0f}, IM_COL32(70, 75, 85, 255), "settle");
    }
    if (!s.bodies.shown) return;
    const auto ticks =
        nice_ticks({0.0, duration}, std::max(2, static_cast<int>((hi.x - lo.x) / 70.0f)));
    const double step = ticks.size() > 1 ? ticks[1] - ticks[0] : 1.0;
    for (double t : ticks) {
        const float x = x_of(t);
        dl->AddLine({x, hi.y - 5.0f}, {x, hi.y}, IM_COL32(90, 90, 90, 255));
        const std::string label = format_tick(t, step) + " s";
        const ImVec2 ts = ImGui::CalcTextSize(label.c_str());
        dl->AddText({std::clamp(x - ts.x * 0.5f, lo.x, hi.x - ts.x), hi.y + 2.0f},
                    IM_COL32(60, 60, 60, 255), label.c_str());
    }
    dl->AddRect(lo, hi, IM_COL32(120, 120, 120, 255));
    if (s.bodies.shown) {
        const float x = x_of(clock.time_s);
        dl->AddLine({x, lo.y}, {x, hi.y}, IM_COL32(214, 69, 56, 255), 2.5f);
        dl->AddTriangleFilled({x - 6.0f, lo.y}, {x + 6.0f, lo.y}, {x, lo.y + 8.0f},
                              IM_COL32(214, 69, 56, 255));
    }
}

}  // namespace

void draw_replay_panel(Studio& s) {
    auto& clock = s.clock;
    ImGui::BeginDisabled(!s.bodies.shown);
    if (tracked_button(s, "|<")) clock.seek(0.0);
    ImGui::SameLine();
    if (tracked_button(s, "<")) step_replay(s, -1);
    ImGui::SameLine();
    if (tracked_button(s, clock.playing ? "Pause##play" : "Play##play",
                       ImVec2(ImGui::GetFontSize() * 4.0f, 0)))
        toggle_playback(s);
    ImGui::SameLine();
    if (tracked_button(s, ">")) step_replay(s, 1);
    ImGui::SameLine();
    if (tracked_button(s, ">|")) clock.seek(clock.duration_s);
    ImGui::SameLine();
    ImGui::SetNextItemWidth(ImGui::GetFontSize() * 5.0f);
    static const double speeds[] = {0.05, 0.1, 0.25, 0.5, 1.0, 2.0, 4.0};
    char speed_text[32];
    std::snprintf(speed_text, sizeof speed_text, "%gx", clock.speed);
    if (ImGui::BeginCombo("speed", speed_text)) {
        for (double v : speeds) {
            std::snprintf(speed_text, sizeof speed_text, "%gx", v);
            if (ImGui::Selectable(speed_text, v == clock.speed)) clock.speed = v;
        }
        ImGui::EndCombo();
    }
    ImGui::SameLine();
    ImGui::Checkbox("loop", &clock.loop);
    ImGui::EndDisabled();
    // The clock beside the buttons where it fits, else under them: a fixed guess of the room
    // left ran "no simulation yet" past the tile at 900x640 (issue 39, the clipped-text low).
    char line[96];
    if (s.bodies.shown) {
        const double settle = s.bodies.shown->experiment.simulation.settle_s;
        std::snprintf(line, sizeof line, "t = %.3f s / %.3f s   %s", clock.time_s, clock.duration_s,
                      clock.time_s < settle ? "(settling, actuation off)" : "(actuated)");
    } else {
        std::snprintf(line, sizeof line, "no simulation yet");
    }
    const float spacing = ImGui::GetStyle().ItemSpacing.x;
    const float row_end = ImGui::GetItemRectMax().x + spacing + ImGui::CalcTextSize(line).x;
    if (row_end <= ImGui::GetWindowPos().x + ImGui::GetWindowContentRegionMax().x)
        ImGui::SameLine();
    if (s.bodies.shown)
        ImGui::TextUnformatted(line);
    else
        ImGui::TextDisabled("%s", line);
    timeline(s, std::max(ImGui::GetContentRegionAvail().y, ImGui::GetFontSize() * 2.5f));
}

}  // namespace bhm::app::gui
