#pragma once
// VoxCAD / Voxelyze VXA 1.0 export of a body under an experiment: simulator damping, gravity and
// floor, thermal actuation, one fixed boundary region per fixed face, the palette in the
// experiment's material order and the lattice as ASCII_READABLE layers (x fastest, then y, one
// <Layer> per z, cell character '0' + material index, so at most 44 materials). Numbers use the C
// locale (engine::format_number). VXA 1.0 cannot express the settle delay before actuation or
// per-voxel fixed overrides; an XML comment in the file mentions the settle delay, and a
// <BHM_Experiment> element (ignored by VoxCAD) holds the whole experiment as JSON so that
// evo/formats/vxa_import.hpp reads our own files back exactly; a body with its own fibre axes
// (issue 43; Voxelyze has no muscle model) adds them as <BHM_Fibres>, the body file's "fibres".
#include <string>

#include "evo/experiment/experiment.hpp"

namespace bhm::evo {

std::string vxa_document(const Experiment& experiment, const Body& body);

//! Writes atomically (temp file + rename); throws std::runtime_error naming the path.
void save_vxa(const std::string& path, const Experiment& experiment, const Body& body);

}  // namespace bhm::evo
