// The studio's material library picker: a slot filled from the library as one undoable edit, by
// the action and by clicks on the Experiment panel (headless, OSMesa).
#include <doctest/doctest.h>

#include <nlohmann/json.hpp>

#include "app/gui/actions/studio_actions.hpp"
#include "app/gui/panels/material_picker.hpp"
#include "app/gui/shell/headless_studio.hpp"
#include "app/gui/shell/script.hpp"
#include "evo/experiment/material_library.hpp"
#include "test_studio_fixtures.hpp"

using namespace bhm;
using namespace bhm::app::gui;
using nlohmann::json;

namespace {
const std::string kLibrary = std::string(BHM_SOURCE_DIR) + "/assets/materials";
bool on_screen(const Studio& s, const std::string& widget) {
    const auto it = s.ui.widgets.find(widget);
    return it != s.ui.widgets.end() && it->second.frame >= s.ui.frame - 1;
}
}  // namespace

TEST_CASE("studio materials: a slot is filled from the library and undone as one edit") {
    Studio studio;
    studio.library.materials_dir = kLibrary;
    studio.document.reset(testing::tiny_experiment(), "");
    const auto original = studio.document.experiment();
    const auto* library = studio_material_library(studio);
    REQUIRE(library != nullptr);
    const auto& ds30 = *library->find("dragon-skin-30");

    REQUIRE(choose_library_material(studio, 0, "dragon-skin-30"));
    const auto& slot = studio.document.experiment().materials[0];
    CHECK(slot.library == "dragon-skin-30");
    CHECK(slot.name == ds30.name);
    CHECK(slot.physics.youngs_modulus_pa == ds30.youngs_modulus_pa.value);
    CHECK(slot.physics.density_kg_m3 == ds30.density_kg_m3->value);
    CHECK(slot.physics.cte_per_c == 0.0);
    // Friction has no source in the library: the slot's own is kept.
    CHECK(slot.physics.static_friction == original.materials[0].physics.static_friction);
    CHECK(fields_changed_from_library(ds30, slot, 14.47).empty());
    auto typed = slot;
    typed.physics.youngs_modulus_pa *= 2;
    CHECK(fields_changed_from_library(ds30, typed, 14.47) == std::vector<std::string>{"E"});

    CHECK(studio.document.undo_label() == "material 1 from library: " + ds30.name);
    REQUIRE(undo(studio));
    CHECK(studio.document.experiment() == original);
    CHECK_FALSE(choose_library_material(studio, 0, "no-such-material"));
    CHECK(studio.document.experiment() == original);

    // The search: every word must match the id, name or category.
    CHECK(library_material_matches(ds30, "dragon 30"));
    CHECK(library_material_matches(ds30, "SILICONE"));
    CHECK_FALSE(library_material_matches(ds30, "dragon tissue"));
    CHECK(library_material_matches(*library->find("cardiomyocyte-tissue"), "active"));
}

TEST_CASE("studio materials: the picker opens, lists the library and fills the slot on a click") {
    Studio studio;
    studio.library.materials_dir = kLibrary;
    studio.document.reset(testing::tiny_experiment(), "");
    HeadlessStudio session(studio, 1280, 800);
    run_script(session, json::parse(R"([{"frames": 2}, {"click": "header Materials"},
                                        {"frames": 2}, {"click": "library 1"}, {"frames": 2}])"));
    CHECK(on_screen(studio, "library item ecoflex-00-50"));
    CHECK(on_screen(studio, "library item skeletal-muscle-engineered"));
    run_script(session, json::parse(R"([{"click": "library item ecoflex-00-50"}, {"frames": 2}])"));
    const auto& slot = studio.document.experiment().materials[0];
    CHECK(slot.library == "ecoflex-00-50");
    CHECK(slot.physics.youngs_modulus_pa ==
          studio_material_library(studio)->find("ecoflex-00-50")->youngs_modulus_pa.value);
    CHECK(studio.document.undo_label().find("from library") != std::string::npos);
}

TEST_CASE("studio materials: the presets gallery lists and opens the biohybrid catheter") {
    Studio studio;
    studio.library.presets_dir = std::string(BHM_SOURCE_DIR) + "/assets/experiments";
    studio.document.reset(testing::tiny_experiment(), "");
    HeadlessStudio session(studio, 1280, 800);
    run_script(session, json::parse(R"([{"click": "tab Files"}, {"frames": 2}])"));
    CHECK(on_screen(studio, "preset biohybrid-catheter"));
    run_script(session,
               json::parse(R"([{"click": "preset biohybrid-catheter"}, {"frames": 2}])"));
    const auto& e = studio.document.experiment();
    CHECK(e.name == "biohybrid-catheter");
    REQUIRE(e.materials.size() == 2);
    CHECK(e.materials[1].library == "skeletal-muscle-engineered");
}
