#pragma once
// The welcome a newcomer sees on first start (issue 25 item 9): a gallery of the shipped presets,
// each with a one-line description (its thumbnail is drawn by welcome_thumbnails.hpp), the quick
// demo first, and a legend of the 3D view's colours. Plain data here, testable without GL.
#include <string>
#include <vector>

#include "evo/experiment/experiment.hpp"

namespace bhm::app::gui {

struct StudioSettings;

//! One preset of the gallery.
struct PresetCard {
    std::string path;     //!< absolute
    std::string stem;     //!< file name without .json ("quick-demo")
    std::string summary;  //!< one line
    std::string description;  //!< the experiment's whole description (the card's tooltip)
    evo::Experiment experiment;  //!< as read (the thumbnail draws its workspace)
};

//! The stem the gallery puts first and names "start here".
inline constexpr const char* kStartHerePreset = "quick-demo";

//! One line for a preset: a caption of our own for the shipped ones, else the description's first
//! sentence, cut at `max_chars` with "...".
std::string preset_summary(const std::string& stem, const std::string& description,
                           std::size_t max_chars = 110);

//! The presets of `dir` that load (the others are skipped, their reasons in *skipped), the quick
//! demo first, then by name.
std::vector<PresetCard> read_preset_cards(const std::string& dir,
                                          std::vector<std::string>* skipped = nullptr);

//! A first start: there is a settings path and either no settings file there yet or no recent
//! experiment in it. Headless runs without --settings-dir keep no settings: never a first start.
bool is_first_start(const std::string& settings_path, bool settings_file_existed,
                    const StudioSettings& settings);

//! The colours and marks of the 3D view, one line each (the welcome's legend and F1).
struct LegendEntry {
    float rgb[3];
    const char* mark;  //!< "face", "cell", "star", "line", "box"
    const char* text;
};
const std::vector<LegendEntry>& view_legend();

}  // namespace bhm::app::gui
