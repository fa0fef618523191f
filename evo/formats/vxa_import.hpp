#pragma once
// VoxCAD / Voxelyze VXA (and bare VXC) import, as VoxCAD 1.0 and Kriegman et al.'s evosoro write
// them. Mapped: the palette (name, colour, E, density, Poisson ratio, CTE, friction), the
// ASCII_READABLE structure layers (x fastest, then y, one <Layer> per z, '0' + material index),
// the lattice dimension, integration DtFrac, the three damping ratios, gravity and floor, thermal
// amplitude (TempAmp or TempAmplitude) and period, the stop time, evosoro's InitCmTime (as the
// settle time), and fixed regions (<Boundary_Conditions><FRegion> or <Fixed_Regions><Region>,
// box regions in workspace fractions, all six DOF fixed) as fixed faces when a region covers
// exactly one face layer, otherwise as per-voxel fixed overrides of the voxels it overlaps.
// Everything else that carries meaning (forces, partial DOF, per-voxel phase or stiffness layers,
// ZLIB-compressed structures, non-linear or failing materials, lattice offsets, evosoro's GA
// settings...) is listed in `unmapped`, one line each. Our own export (evo/formats/vxa.hpp) embeds the
// whole experiment as JSON in a <BHM_Experiment> element that VoxCAD ignores: with it, import
// gives back exactly the exported experiment and body.
#include <string>
#include <vector>

#include "evo/experiment/experiment.hpp"

namespace bhm::evo {

struct VxaImport {
    Experiment experiment;
    Body body;                          //!< the structure, workspace-sized
    std::vector<std::string> unmapped;  //!< what the file holds that BHM cannot express
    bool had_bhm_experiment = false;    //!< our own export: the embedded experiment was the base
};

//! Parses VXA/VXC text; throws std::runtime_error "label: line N: what" or "label: Field: what"
//! when the file is not a usable VXA (malformed XML, no palette or structure, bad layer).
VxaImport parse_vxa(const std::string& text, const std::string& label);

//! Reads and parses a file; throws std::runtime_error naming it.
VxaImport load_vxa(const std::string& path);

}  // namespace bhm::evo
