// Issue 39's "clipped text" low, seen in a real window: at 1600x1000 the Analysis tabs were cut
// ("Populat..."), a long experiment description ran off the Experiment panel on one line, and at
// 900x640 "no simulation yet" ran past the Replay tile. Measured here on ImGui's own record of
// what it laid out (the tab bar's tabs, a window's content extent), not on the studio's code.
#include <doctest/doctest.h>

#include <filesystem>
#include <memory>
#include <string>

#include <imgui.h>
#include <imgui_internal.h>  // the tab bar's tabs and a window's content size

#include "app/gui/session/fem_verifier.hpp"
#include "app/gui/shell/headless_studio.hpp"
#include "app/gui/shell/script.hpp"
#include "test_studio_fixtures.hpp"

using namespace bhm;
using namespace bhm::app::gui;
using nlohmann::json;

namespace {

const ImGuiWindow& tile(const char* name) {
    const ImGuiWindow* window = ImGui::FindWindowByName(name);
    REQUIRE(window);
    return *window;
}

// The Analysis tile's tab bar, as ImGui laid it out in the last frame.
const ImGuiTabBar& analysis_tab_bar() {
    const ImGuiWindow& window = tile("Analysis");
    const ImGuiTabBar* bar =
        ImGui::GetCurrentContext()->TabBars.GetByKey(ImHashStr("analysis tabs", 0, window.ID));
    REQUIRE(bar);
    return *bar;
}

// Every tab at least as wide as its label (ImGui shrinks tabs that do not fit and cuts their
// labels to "Populat..."), and every tab inside the tile, so none is out of reach.
void check_tabs_whole(const Studio& studio) {
    const ImGuiTabBar& bar = analysis_tab_bar();
    const ImGuiWindow& window = tile("Analysis");
    CHECK(bar.Tabs.Size == 8);
    for (const ImGuiTabItem& tab : bar.Tabs) {
        INFO("tab \"" << std::string(bar.GetTabName(&tab)) << "\": " << tab.Width
                      << " px for a label of " << tab.ContentWidth << " px");
        CHECK(tab.Width >= tab.ContentWidth - 0.5f);
        CHECK(bar.BarRect.Min.x + tab.Offset + tab.Width <= window.Pos.x + window.Size.x);
    }
    for (const char* name : {"Population", "Champions", "Age vs fitness", "Volume vs fitness",
                             "Time plots", "Calibrate", "FEM", "Robustness"}) {
        const WidgetRect r = studio.ui.widgets.at(std::string("tab ") + name);
        INFO("tab " << std::string(name) << " from x " << r.min.x << " to " << r.max.x);
        CHECK(r.min.x >= window.Pos.x);
        CHECK(r.max.x <= window.Pos.x + window.Size.x);
        CHECK(r.max.x - r.min.x > 10.0f);
    }
}

// How far the tile's content (its widest line last frame) runs past the tile's inner width.
float overflow_px(const char* name) {
    const ImGuiWindow& window = tile(name);
    const float inner = window.Size.x - 2.0f * window.WindowPadding.x - window.ScrollbarSizes.x;
    return window.ContentSize.x - inner;
}

}  // namespace

TEST_CASE("studio clipped text: every Analysis tab shows its whole label, with any tab open") {
    for (const auto& [w, h] : {std::pair{1600, 1000}, std::pair{1280, 800}}) {
        INFO(w << " x " << h);
        Studio studio;
        studio.document.reset(testing::tiny_experiment(), "");
        HeadlessStudio session(studio, w, h);
        run_script(session, json::parse(R"([{"frames": 3}])"));
        check_tabs_whole(studio);
        // A tab whose content scrolls narrows the bar by the scrollbar: still whole, and each
        // tab (FEM and Calibrate among them, which the other studio tests click) opens.
        for (const char* name : {"Population", "Champions", "Age vs fitness", "Volume vs fitness",
                                 "Time plots", "Calibrate", "FEM", "Robustness"}) {
            INFO("after clicking " << std::string(name));
            run_script(session, json{{{"click", std::string("tab ") + name}}, {{"frames", 2}}});
            const ImGuiTabBar& bar = analysis_tab_bar();
            const ImGuiTabItem* selected = nullptr;
            for (const ImGuiTabItem& tab : bar.Tabs)
                if (tab.ID == bar.SelectedTabId) selected = &tab;
            REQUIRE(selected);
            CHECK(std::string(bar.GetTabName(selected)).ends_with(name));
            check_tabs_whole(studio);
        }
    }
}

TEST_CASE("studio clipped text: a long description wraps inside the Experiment panel") {
    evo::Experiment e = testing::tiny_experiment();
    e.description =
        "A bending actuator for a catheter tip, held at its base: the passive tissue carries the "
        "muscle strip along one side, and the strip contracts at two hertz after the body has "
        "settled under gravity for a second. The fitness is the bend angle of the free end, "
        "measured against the straight rest shape, so that a body which only drifts scores zero.";
    Studio studio;
    studio.document.reset(e, "");
    HeadlessStudio session(studio, 1600, 1000);
    run_script(session, json::parse(R"([{"frames": 3}])"));
    const ImGuiWindow& design = tile("Design");
    const WidgetRect shown = studio.ui.widgets.at("description");
    const float width = shown.max.x - shown.min.x;
    const float wrapped =
        ImGui::CalcTextSize(e.description.c_str(), nullptr, false, width - 8.0f).y;
    INFO("description box " << width << " x " << shown.max.y - shown.min.y << " px; its text, "
                            << "wrapped to that width, " << wrapped << " px high");
    CHECK(shown.min.x >= design.Pos.x);
    CHECK(shown.max.x <= design.Pos.x + design.Size.x);
    // Every wrapped line is in the box (one line runs off the right of an unwrapped text box).
    CHECK(shown.max.y - shown.min.y >= wrapped);
    CHECK(overflow_px("Design") <= 0.5f);

    // It is still edited in place: a click opens the text for typing with the caret at its end,
    // a click elsewhere keeps the edit and shows it wrapped again.
    run_script(session, json::parse(R"([{"click": "description"}, {"frames": 2},
                                        {"type": " Edited."},
                                        {"click": "tab Experiment"}, {"frames": 2}])"));
    CHECK(studio.document.experiment().description == e.description + " Edited.");
    const WidgetRect after = studio.ui.widgets.at("description");
    CHECK(after.max.y - after.min.y >= wrapped);
}

TEST_CASE("studio clipped text: the Replay tile's line fits its width with no body shown") {
    for (const auto& [w, h] : {std::pair{900, 640}, std::pair{1280, 800}, std::pair{1600, 1000}}) {
        INFO(w << " x " << h);
        Studio studio;
        studio.document.reset(testing::tiny_experiment(), "");
        HeadlessStudio session(studio, w, h);
        run_script(session, json::parse(R"([{"frames": 3}])"));
        CHECK(overflow_px("Replay") <= 0.5f);
    }
}

TEST_CASE("studio clipped text: the FEM tab's hints wrap inside a narrow Analysis tile") {
    // At 400 px the FEM tab cut three hints (the CalculiX line with the report's folder, the
    // ghost's hint beside its box, the table's legend) and the prompt beside Verify in FEM: a
    // TextDisabled line never wraps. The report is the one kept in tests/data (no solve).
    auto kept = read_verification(
        (std::filesystem::path(BHM_SOURCE_DIR) / "tests" / "data" / "verify" / "individual-7")
            .string(),
        7);
    REQUIRE(kept);
    kept->dir = "/home/researcher/runs/catheter-tip-2026-12-06/verify/individual-7";
    int tables_drawn = 0;
    for (const auto& [w, h] :
         {std::pair{900, 640}, std::pair{1024, 700}, std::pair{1280, 800}, std::pair{1600, 1000}}) {
        Studio studio;
        studio.document.reset(testing::tiny_experiment(), "");
        studio.verify.result = std::make_shared<const FemVerification>(*kept);
        HeadlessStudio session(studio, w, h);
        run_script(session, json::parse(R"([{"frames": 2}, {"click": "tab FEM"}, {"frames": 3}])"));
        const ImGuiWindow& analysis = tile("Analysis");
        INFO(w << " x " << h << ": the Analysis tile is " << analysis.Size.x << " px wide, its "
               << "content " << analysis.ContentSize.x << " px");
        CHECK(overflow_px("Analysis") <= 0.5f);
        // The per-load table scrolls sideways inside the tile rather than widening it (a short
        // tile scrolls the table out of view: then it has no row this frame).
        const auto row = studio.ui.widgets.find("fem load rest");
        if (row != studio.ui.widgets.end() && row->second.frame == studio.ui.frame) {
            CHECK(row->second.max.x <= analysis.Pos.x + analysis.Size.x);
            ++tables_drawn;
        }
    }
    CHECK(tables_drawn >= 1);
}
