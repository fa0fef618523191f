#include "app/gui/welcome/welcome.hpp"

#include <algorithm>
#include <filesystem>
#include <map>

#include "app/gui/settings/studio_paths.hpp"
#include "app/gui/studio.hpp"
#include "evo/experiment/experiment_io.hpp"
#include "render/scene.hpp"

namespace bhm::app::gui {

namespace fs = std::filesystem;

namespace {

// The shipped presets' descriptions are paragraphs (sources, budgets, caveats): the gallery
// needs one line a newcomer can choose from. Their full text stays in the card's tooltip.
const std::map<std::string, std::string>& shipped_captions() {
    static const std::map<std::string, std::string> captions = {
        {"quick-demo", "a small bending actuator: 5 generations in about two minutes"},
        {"multi-material", "the quick demo with a third, stiffer scaffold material"},
        {"biohybrid-catheter",
         "a catheter tip of Ecoflex and engineered muscle that bends (quick budget)"},
        {"paper-exp1", "paper experiment 1: move the centre of mass, 8x8x7 (48 h)"},
        {"paper-exp1-attached", "paper experiment 1, the body attached to the fixed face (48 h)"},
        {"paper-exp2", "paper experiment 2: a longer 20x8x7 workspace, tentacles may cheat (48 h)"},
        {"paper-exp3", "paper experiment 3: inside a passive enclosure, YZ displacement (48 h)"},
    };
    return captions;
}

}  // namespace

std::string preset_summary(const std::string& stem, const std::string& description,
                           std::size_t max_chars) {
    const auto& captions = shipped_captions();
    if (const auto it = captions.find(stem); it != captions.end()) return it->second;
    std::string line = description.substr(0, description.find('\n'));
    if (const auto end = line.find(". "); end != std::string::npos) line = line.substr(0, end + 1);
    if (line.empty()) return "(no description)";
    if (line.size() > max_chars) line = line.substr(0, max_chars - 3) + "...";
    return line;
}

std::vector<PresetCard> read_preset_cards(const std::string& dir,
                                          std::vector<std::string>* skipped) {
    std::vector<PresetCard> cards;
    for (const auto& path : list_experiment_files(dir)) {
        try {
            PresetCard card;
            card.experiment = evo::load_experiment(path);
            card.path = path;
            card.stem = fs::path(path).stem().string();
            card.description = card.experiment.description;
            card.summary = preset_summary(card.stem, card.description);
            cards.push_back(std::move(card));
        } catch (const std::exception& e) {
            if (skipped) skipped->push_back(path + ": " + e.what());
        }
    }
    // The quick demo first; the rest keep the folder's order (by name).
    std::stable_partition(cards.begin(), cards.end(),
                          [](const PresetCard& c) { return c.stem == kStartHerePreset; });
    return cards;
}

bool is_first_start(const std::string& settings_path, bool settings_file_existed,
                    const StudioSettings& settings) {
    if (settings_path.empty()) return false;
    return !settings_file_existed || settings.recent_files.empty();
}

const std::vector<LegendEntry>& view_legend() {
    using namespace render::palette;
    static const std::vector<LegendEntry> legend = {
        {{kFixedFace.r, kFixedFace.g, kFixedFace.b},
         "face",
         "green face: fixed (the body is held there)"},
        {{kFreeFace.r, kFreeFace.g, kFreeFace.b}, "face", "purple face: free"},
        {{kEnclosure.r * 0.8f, kEnclosure.g * 0.8f, kEnclosure.b * 0.8f},
         "cell",
         "grey translucent cell: the enclosure frame"},
        {{0.25f, 0.25f, 0.28f}, "cell", "dark cell: forbidden, evolution may not fill it"},
        {{kFixedHatch.r, kFixedHatch.g, kFixedHatch.b}, "hatch", "hatched: held voxels"},
        {{kActive.r, kActive.g, kActive.b}, "cell", "red voxel: muscle (active)"},
        {{kPassive.r, kPassive.g, kPassive.b}, "cell", "blue voxel: passive tissue"},
        {{kStar.r, kStar.g, kStar.b}, "star", "yellow star: the body's cell (0, 0, 0)"},
        {{kComTrail.r, kComTrail.g, kComTrail.b}, "line", "orange line: centre-of-mass trail"},
        {{0.93f, 0.49f, 0.13f}, "box", "orange box: the voxel clicked in Simulation mode"},
    };
    return legend;
}

}  // namespace bhm::app::gui
