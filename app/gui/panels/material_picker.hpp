#pragma once
// The Experiment panel's material library picker (docs/materials-format.md): per material slot a
// button that opens a searchable list of the library with each material's values and sources;
// choosing one fills the slot (choose_library_material), typing in the fields below overrides it.
#include <cstddef>
#include <string>
#include <vector>

#include "app/gui/studio.hpp"

namespace bhm::app::gui {

//! Whether a library material matches the picker's search text (case-insensitive, in its id, name
//! or category; every space-separated word must match).
bool library_material_matches(const evo::LibraryMaterial& m, const std::string& filter);
//! The slot's fields that differ from what the library material would give it ("E", "nu", ...).
std::vector<std::string> fields_changed_from_library(const evo::LibraryMaterial& m,
                                                     const evo::MaterialEntry& entry,
                                                     double temperature_amplitude_c);

//! Draws the picker for slot (0-based) of studio.draft; recorded for scripts as "library N"
//! (1-based) and each list entry as "library item ID".
void material_library_picker(Studio& studio, std::size_t slot);

}  // namespace bhm::app::gui
