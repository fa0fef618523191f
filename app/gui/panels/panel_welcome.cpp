// The welcome of a first start (issue 25 item 9): what the studio is for in two lines, the
// shipped presets as a gallery (thumbnail drawn by our renderer, name, one line; "start here:
// quick demo" first), and a legend of the 3D view's colours and marks. Start waits until it is
// closed (by choosing a preset, an empty experiment, or Close).
#include <algorithm>
#include <cmath>
#include <cstdint>
#include <string>

#include <imgui.h>

#include "app/gui/actions/studio_actions.hpp"
#include "app/gui/actions/unsaved_guard.hpp"
#include "app/gui/panels/panels.hpp"
#include "app/gui/welcome/thumbnails.hpp"
#include "app/gui/widgets/ui_widgets.hpp"

namespace bhm::app::gui {

namespace {

constexpr int kThumbW = 168, kThumbH = 104;

// One card: the thumbnail over the name and its line; the whole card is one button.
void card(Studio& s, std::size_t i, unsigned texture, float width) {
    const PresetCard& c = s.ui.welcome_cards[i];
    const bool start_here = c.stem == kStartHerePreset;
    ImGui::PushID(static_cast<int>(i));
    ImGui::BeginGroup();
    const ImVec2 at = ImGui::GetCursorScreenPos();
    const float text_h = ImGui::GetTextLineHeightWithSpacing() * 4.0f;
    const bool chosen =
        ImGui::Selectable("##card", false, 0, ImVec2(width, kThumbH + text_h + 6.0f));
    record_widget(s, "welcome preset " + c.stem);
    if (ImGui::IsItemHovered()) wrapped_tooltip(c.path + "\n\n" + c.description);
    ImDrawList* dl = ImGui::GetWindowDrawList();
    const ImVec2 img{at.x + (width - kThumbW) * 0.5f, at.y + 2.0f};
    if (texture) {
        dl->AddImage(reinterpret_cast<ImTextureID>(static_cast<std::intptr_t>(texture)), img,
                     {img.x + kThumbW, img.y + kThumbH}, {0, 1}, {1, 0});
        s.ui.widgets["welcome thumbnail " + c.stem] =
            WidgetRect{{img.x, img.y}, {img.x + kThumbW, img.y + kThumbH}, s.ui.frame};
    }
    dl->AddRect(img, {img.x + kThumbW, img.y + kThumbH},
                start_here ? IM_COL32(190, 110, 0, 255) : IM_COL32(0, 0, 0, 40), 3.0f, 0,
                start_here ? 2.0f : 1.0f);
    const ImU32 dark = IM_COL32(30, 34, 40, 255);
    const std::string title = start_here ? "start here: quick demo" : c.stem;
    dl->AddText({at.x + 4.0f, img.y + kThumbH + 4.0f},
                start_here ? IM_COL32(170, 95, 0, 255) : dark, title.c_str());
    dl->AddText(nullptr, 0.0f,
                {at.x + 4.0f, img.y + kThumbH + 4.0f + ImGui::GetTextLineHeightWithSpacing()},
                IM_COL32(70, 76, 86, 255), c.summary.c_str(), nullptr, width - 8.0f);
    ImGui::EndGroup();
    ImGui::PopID();
    if (chosen) {
        s.ui.welcome_open = false;
        const bool already = s.document.path() == c.path && !s.document.dirty();
        if (!already) request_open_experiment(s, c.path);
    }
}

void legend(Studio& s) {
    section_title("Reading the 3D view");
    const ImVec2 start = ImGui::GetCursorScreenPos();
    const float line = ImGui::GetTextLineHeightWithSpacing();
    const float box = ImGui::GetFontSize() * 0.9f;
    ImDrawList* dl = ImGui::GetWindowDrawList();
    const auto& entries = view_legend();
    const float column = (ImGui::GetContentRegionAvail().x - 8.0f) * 0.5f;
    const std::size_t rows = (entries.size() + 1) / 2;
    for (std::size_t k = 0; k < entries.size(); ++k) {
        const auto& e = entries[k];
        const ImVec2 at{start.x + (k < rows ? 0.0f : column), start.y + line * float(k % rows)};
        const ImU32 colour =
            ImGui::ColorConvertFloat4ToU32(ImVec4(e.rgb[0], e.rgb[1], e.rgb[2], 1));
        const ImVec2 lo{at.x, at.y + 2.0f}, hi{at.x + box, at.y + 2.0f + box};
        const std::string mark = e.mark;
        if (mark == "star") {
            const ImVec2 c{(lo.x + hi.x) * 0.5f, (lo.y + hi.y) * 0.5f};
            ImVec2 p[10];
            for (int j = 0; j < 10; ++j) {
                const float r = (j % 2 ? 0.22f : 0.55f) * box;
                const float a = -1.5708f + 0.6283f * float(j);
                p[j] = {c.x + r * std::cos(a), c.y + r * std::sin(a)};
            }
            // Each point: the triangles to the inner corners on either side of it.
            for (int j = 0; j < 10; j += 2) {
                dl->AddTriangleFilled(c, p[j], p[(j + 1) % 10], colour);
                dl->AddTriangleFilled(c, p[(j + 9) % 10], p[j], colour);
            }
        } else if (mark == "line") {
            dl->AddLine({lo.x, (lo.y + hi.y) * 0.5f}, {hi.x, (lo.y + hi.y) * 0.5f}, colour, 3.0f);
        } else if (mark == "box") {
            dl->AddRect(lo, hi, colour, 0.0f, 0, 2.0f);
        } else if (mark == "hatch") {
            dl->AddRect(lo, hi, colour);
            for (float d = 0.0f; d < box * 2.0f; d += box * 0.4f) {
                const float x0 = lo.x + std::max(0.0f, d - box), y0 = hi.y - std::min(d, box);
                const float x1 = lo.x + std::min(d, box), y1 = hi.y - std::max(0.0f, d - box);
                dl->AddLine({x0, y0}, {x1, y1}, colour);
            }
        } else {
            dl->AddRectFilled(lo, hi, colour, 2.0f);
            dl->AddRect(lo, hi, IM_COL32(0, 0, 0, 60), 2.0f);
        }
        dl->AddText({hi.x + 6.0f, at.y}, IM_COL32(30, 34, 40, 255), e.text);
    }
    const float height = line * float(rows);
    ImGui::Dummy(ImVec2(column * 2.0f, height));
    s.ui.widgets["welcome legend"] =
        WidgetRect{{start.x, start.y}, {start.x + column * 2.0f, start.y + height}, s.ui.frame};
    ImGui::TextWrapped(
        "Click a voxel in Simulation mode to read its material, displacement, strain and "
        "actuation; F1 lists every shortcut.");
}

}  // namespace

void draw_welcome_window(Studio& s, ViewRenderer& renderer, WelcomeThumbnails& thumbnails) {
    if (!s.ui.welcome_open) return;
    thumbnails.ensure(renderer, s.ui.welcome_cards, kThumbW, kThumbH, s.view.samples);
    centre_next_window(62.0f, 46.0f, ImGuiCond_Always);
    ImGui::SetNextWindowFocus();
    bool open = true;
    if (!ImGui::Begin("Welcome to BHM Studio", &open,
                      ImGuiWindowFlags_NoCollapse | ImGuiWindowFlags_NoMove |
                          ImGuiWindowFlags_NoResize | ImGuiWindowFlags_NoSavedSettings)) {
        ImGui::End();
        return;
    }
    {
        const ImVec2 pos = ImGui::GetWindowPos(), size = ImGui::GetWindowSize();
        s.ui.widgets["welcome window"] =
            WidgetRect{{pos.x, pos.y}, {pos.x + size.x, pos.y + size.y}, s.ui.frame};
    }
    ImGui::TextWrapped(
        "BHM Studio evolves soft biohybrid actuators: describe the design problem, run "
        "evolution, watch the champion bend. Choose an experiment to start from (the quick demo "
        "is open behind this window); Start waits until you have chosen.");
    // The gallery and legend scroll; the buttons under them stay in sight.
    const float footer =
        ImGui::GetFrameHeightWithSpacing() + ImGui::GetStyle().ItemSpacing.y * 2.0f;
    ImGui::BeginChild("welcome body", ImVec2(0, -footer));
    section_title("Presets");
    if (s.ui.welcome_cards.empty())
        ImGui::TextDisabled("no presets in %s", s.library.presets_dir.c_str());
    const float card_w = kThumbW + 24.0f;
    const int per_row = std::max(1, static_cast<int>(ImGui::GetContentRegionAvail().x /
                                                     (card_w + ImGui::GetStyle().ItemSpacing.x)));
    for (std::size_t i = 0; i < s.ui.welcome_cards.size() && s.ui.welcome_open; ++i) {
        if (i % static_cast<std::size_t>(per_row) != 0) ImGui::SameLine();
        card(s, i, thumbnails.texture(i), card_w);
    }
    if (s.ui.welcome_open) legend(s);
    ImGui::EndChild();
    ImGui::Separator();
    if (tracked_button(s, "Empty experiment")) {
        s.ui.welcome_open = false;
        request_new_experiment(s);
    }
    if (ImGui::IsItemHovered())
        wrapped_tooltip("the paper's materials on an 8x8x7 workspace held at x- "
                        "(the paper's 2000 generations and 48 h: set the budget first)");
    ImGui::SameLine();
    if (tracked_button(s, "Close")) s.ui.welcome_open = false;
    if (!open) s.ui.welcome_open = false;
    ImGui::End();
}

}  // namespace bhm::app::gui
