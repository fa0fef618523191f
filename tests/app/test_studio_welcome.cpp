// The first start (issue 25 item 9): a welcome with the presets' gallery (thumbnails drawn by our
// renderer, one line each, the quick demo first), a legend of the 3D view, the quick demo in the
// editor instead of an untitled paper-sized experiment, and Start held until the welcome closes.
#include <doctest/doctest.h>

#include <algorithm>
#include <filesystem>
#include <set>

#include <imgui_internal.h>  // the tooltip window

#include "app/gui/actions/studio_actions.hpp"
#include "app/gui/shell/headless_studio.hpp"
#include "app/gui/shell/script.hpp"
#include "app/gui/welcome/example_body.hpp"
#include "app/gui/welcome/welcome.hpp"
#include "evo/genome/phenotype.hpp"
#include "test_studio_fixtures.hpp"

using namespace bhm;
using namespace bhm::app::gui;
using nlohmann::json;
namespace fs = std::filesystem;

namespace {

const std::string kPresets = std::string(BHM_SOURCE_DIR) + "/assets/experiments";

// Distinct colours inside a widget's rectangle of a capture (top row first).
std::size_t colours_in(const render::Image& image, const WidgetRect& r) {
    std::set<std::uint32_t> seen;
    for (int y = static_cast<int>(r.min.y) + 2; y < static_cast<int>(r.max.y) - 2; ++y)
        for (int x = static_cast<int>(r.min.x) + 2; x < static_cast<int>(r.max.x) - 2; ++x) {
            const std::size_t at =
                static_cast<std::size_t>(y) * static_cast<std::size_t>(image.width) +
                static_cast<std::size_t>(x);
            const auto* p = &image.rgba[4 * at];
            seen.insert(static_cast<std::uint32_t>(p[0] | (p[1] << 8) | (p[2] << 16)));
        }
    return seen.size();
}

// Pixels of a widget's rectangle in the muscle's red (shaded or not): in the empty workspace only
// the x axis (green and purple faces, grey frame, yellow star).
std::size_t red_pixels(const render::Image& image, const WidgetRect& r) {
    std::size_t n = 0;
    for (int y = static_cast<int>(r.min.y) + 2; y < static_cast<int>(r.max.y) - 2; ++y)
        for (int x = static_cast<int>(r.min.x) + 2; x < static_cast<int>(r.max.x) - 2; ++x) {
            const std::size_t at =
                static_cast<std::size_t>(y) * static_cast<std::size_t>(image.width) +
                static_cast<std::size_t>(x);
            const int red = image.rgba[4 * at], green = image.rgba[4 * at + 1],
                      blue = image.rgba[4 * at + 2];
            if (red > 90 && red * 10 > green * 16 && red * 10 > blue * 16) ++n;
        }
    return n;
}

}  // namespace

TEST_CASE("studio welcome: each preset's example body is a generation-0 body that fills a tenth") {
    for (const auto& c : read_preset_cards(kPresets)) {
        CAPTURE(c.stem);
        const auto body = example_body(c.experiment);
        REQUIRE(body);
        CHECK(body->size == c.experiment.workspace_size);
        // At least a tenth of the design space filled (a one-voxel body would show nothing),
        // counted here over the design space's cells.
        const auto space = evo::design_space(c.experiment);
        int designed = 0, active = 0;
        for (int z = 0; z < body->size[2]; ++z)
            for (int y = 0; y < body->size[1]; ++y)
                for (int x = 0; x < body->size[0]; ++x) {
                    const int m = body->cells[static_cast<std::size_t>(body->index(x, y, z))];
                    if (m != 0 && space.contains(x, y, z)) ++designed;
                    if (m != 0 && c.experiment.materials[static_cast<std::size_t>(m - 1)].active())
                        ++active;
                }
        CHECK(designed * 10 >= space.cell_count());
        CHECK(active >= c.experiment.fitness.constraints.min_active_voxels);
        // The same body at every start.
        CHECK(example_body(c.experiment)->cells == body->cells);
    }
    // An experiment that cannot develop a body (no active material): none, the workspace alone.
    auto passive_only = read_preset_cards(kPresets).front().experiment;
    passive_only.materials.resize(1);
    CHECK_FALSE(example_body(passive_only));
}

TEST_CASE("studio welcome: every shipped preset has one line, the quick demo comes first") {
    std::vector<std::string> skipped;
    const auto cards = read_preset_cards(kPresets, &skipped);
    CHECK(skipped.empty());
    REQUIRE(cards.size() == list_experiment_files(kPresets).size());
    REQUIRE(cards.size() >= 2);
    CHECK(cards.front().stem == "quick-demo");
    for (const auto& c : cards) {
        CAPTURE(c.stem);
        CHECK_FALSE(c.summary.empty());
        CHECK(c.summary.size() <= 110);
        CHECK(c.summary.find('\n') == std::string::npos);
        CHECK(c.summary != c.description);  // the paragraphs are the tooltip, not the line
    }
    // A preset of the user's own: the first sentence, cut to the line.
    CHECK(preset_summary("mine", "Bends well. Then more text.") == "Bends well.");
    const std::string long_text(300, 'a');
    CHECK(preset_summary("mine", long_text, 50) == std::string(47, 'a') + "...");
    CHECK(preset_summary("mine", "") == "(no description)");
}

TEST_CASE("studio welcome: a first start is a settings path without a file or a recent file") {
    StudioSettings settings;
    CHECK_FALSE(is_first_start("", false, settings));  // headless, no settings kept
    CHECK(is_first_start("/x/settings.json", false, settings));
    CHECK(is_first_start("/x/settings.json", true, settings));  // no recent experiment
    settings.remember("/x/a.json");
    CHECK_FALSE(is_first_start("/x/settings.json", true, settings));
}

TEST_CASE("studio welcome: the gallery, thumbnails, legend, and Start held until a choice") {
    Studio studio;
    studio.library.presets_dir = kPresets;
    REQUIRE(open_welcome(studio));
    // Not "untitled" with 2000 generations and 48 h: the quick demo, not a recent file.
    const auto& e = studio.document.experiment();
    CHECK(e.name == "quick-demo");
    CHECK(e.evolution.generations <= 10);
    CHECK(e.evolution.wall_budget_h <= 1.0);
    CHECK(studio.settings.recent_files.empty());

    HeadlessStudio session(studio, 1280, 800);
    run_script(session, json::parse(R"([{"frames": 2}])"));
    REQUIRE(studio.ui.welcome_open);
    const auto& w = studio.ui.widgets;
    REQUIRE(w.count("welcome preset quick-demo"));
    REQUIRE(w.count("welcome legend"));
    const float first_y = w.at("welcome preset quick-demo").min.y;
    const float first_x = w.at("welcome preset quick-demo").min.x;
    const render::Image image = session.capture();
    for (const auto& c : studio.ui.welcome_cards) {
        CAPTURE(c.stem);
        REQUIRE(w.count("welcome preset " + c.stem));
        const auto& r = w.at("welcome preset " + c.stem);
        CHECK(r.frame == studio.ui.frame);
        if (c.stem != "quick-demo")  // reading order: the demo is the first card
            CHECK((r.min.y > first_y || (r.min.y == first_y && r.min.x > first_x)));
        // A thumbnail drawn by the renderer: shaded faces, edges and floor, not a flat box.
        REQUIRE(w.count("welcome thumbnail " + c.stem));
        CHECK(colours_in(image, w.at("welcome thumbnail " + c.stem)) > 40);
        // Not the empty workspace: the example body's muscle (every preset asks for one). The
        // red x axis alone gives 64 pixels at this size; the bodies 150 to 1100.
        CHECK(red_pixels(image, w.at("welcome thumbnail " + c.stem)) > 100);
    }

    // Start (the button and F5) waits for a choice.
    run_script(session, json::parse(R"([{"click": "Start"}, {"key": "f5"}, {"frames": 2}])"));
    CHECK(studio.run.evolution.phase() == RunPhase::Idle);
    CHECK_FALSE(start_run(studio));
    CHECK(studio.ui.status.find("welcome") != std::string::npos);

    // A preset's card opens it and closes the welcome.
    run_script(session, json::parse(R"([{"click": "welcome preset paper-exp3"}, {"frames": 2}])"));
    CHECK_FALSE(studio.ui.welcome_open);
    CHECK(studio.document.experiment().name == "paper-exp3");
    CHECK(studio.ui.widgets.at("welcome window").frame < studio.ui.frame);
    CHECK(studio.settings.recent_files.size() == 1);  // chosen by the user: recent
}

TEST_CASE("studio welcome: Close keeps the quick demo, and Start is offered again") {
    Studio studio;
    studio.library.presets_dir = kPresets;
    REQUIRE(open_welcome(studio));
    HeadlessStudio session(studio, 1024, 700);
    run_script(session, json::parse(R"([{"click": "Close"}, {"frames": 2}])"));
    CHECK_FALSE(studio.ui.welcome_open);
    CHECK(studio.document.experiment().name == "quick-demo");
    CHECK_FALSE(studio.document.dirty());
}

TEST_CASE("studio welcome: a card's tooltip (its whole description) stays on the screen") {
    // Issue 39, a low: hovering a preset showed its description as one line running off the
    // right of the screen.
    Studio studio;
    studio.library.presets_dir = kPresets;
    REQUIRE(open_welcome(studio));
    HeadlessStudio session(studio, 1280, 800);
    run_script(session, json::parse(R"([{"frames": 2}])"));
    const auto longest =
        std::max_element(studio.ui.welcome_cards.begin(), studio.ui.welcome_cards.end(),
                         [](const PresetCard& a, const PresetCard& b) {
                             return a.description.size() < b.description.size();
                         });
    REQUIRE(longest != studio.ui.welcome_cards.end());
    REQUIRE(longest->description.size() > 200);  // a paragraph, wider than the screen on one line
    const auto card = studio.ui.widgets.at("welcome preset " + longest->stem);
    session.input().mouse = {(card.min.x + card.max.x) * 0.5f, (card.min.y + card.max.y) * 0.5f};
    session.frame();
    session.frame();
    const ImGuiWindow* tooltip = ImGui::FindWindowByName("##Tooltip_00");
    REQUIRE(tooltip);
    REQUIRE(tooltip->Active);
    INFO("tooltip at x " << tooltip->Pos.x << ", " << tooltip->Size.x << " px wide");
    CHECK(tooltip->Pos.x >= 0.0f);
    CHECK(tooltip->Pos.x + tooltip->Size.x <= 1280.0f);
    CHECK(tooltip->Pos.y + tooltip->Size.y <= 800.0f);
}
