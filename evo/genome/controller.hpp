#pragma once
// The controller genome (issue 44): a CPPN over voxel coordinates, the same genes, operators and
// JSON as the body's (evo/genome/genome.hpp), with two outputs that set each active voxel's drive:
//   output 0 (node kInputCount)     -> phase = pi o, wrapped onto [-pi, pi] (a phase is periodic:
//                                      no output value is saturated, o and o + 2 are one phase);
//   output 1 (node kInputCount + 1) -> amplitude scale = clamp((1 + o) / 2, 0, 1) (0 at o <= -1,
//                                      full drive at o >= 1, one half at o = 0).
// On a muscle voxel the phase is its stimulus timing: a delay of phase / (2 pi) of the stimulus
// period (engine/muscle.hpp, delay_bin).
// Inputs: x, y, z, d, bias over the lattice of the body it drives (the framed workspace),
// mapped as the body CPPN's (evo/genome/cppn_decoder.hpp), so one controller paints any body.
// Passive cells keep phase 0 and amplitude 1 (they are not driven). The engine takes the result
// as BodySpec::phase_rad and amplitude_scale.
// A controller file may instead hold a HyperNEAT CPPN with its substrate (a HyperNEAT fixed_body
// run's champion): the substrate is laid over the lattice of whichever body it drives, so it too
// drives any body (docs/hyperneat.md, "Controller files").
#include <cstdint>
#include <optional>
#include <string>

#include <nlohmann/json.hpp>

#include "evo/experiment/experiment.hpp"
#include "evo/genome/genome.hpp"
#include "evo/genome/rng.hpp"

namespace bhm::evo {

inline constexpr int kControllerOutputCount = 2;
inline constexpr const char* kControllerFileFormat = "bhm-controller";
inline constexpr const char* kControllerFile = "controller.json";

//! The output maps above, for one cell.
float controller_phase(double output);
float controller_amplitude(double output);

//! A new random controller CPPN (random_genome with two outputs).
Genome random_controller(const CppnSettings& settings, Rng& rng);

//! Sets body.phase and body.amplitude (one per cell of body) from the controller's CPPN.
//! Throws std::invalid_argument when the genome does not have two outputs.
void paint_controller(const Genome& controller, const std::vector<MaterialEntry>& materials,
                      Body& body);
//! The same from the two outputs' values per cell of body (HyperNEAT's substrate gives them).
void paint_controller_outputs(const std::vector<double>& phase,
                              const std::vector<double>& amplitude,
                              const std::vector<MaterialEntry>& materials, Body& body);

//! A built-in controller by name (ControllerEntry): "uniform", "random" (seeded) or "wave".
//! Throws std::invalid_argument for another name.
void paint_builtin_controller(const std::string& name, std::uint64_t seed,
                              const std::vector<MaterialEntry>& materials, Body& body);
//! An entry of evolution.controller.controllers: a built-in or a controller file's CPPN.
void paint_controller_entry(const ControllerEntry& entry, double weight_range,
                            const std::vector<MaterialEntry>& materials, Body& body);

//! controller.json: {"format": "bhm-controller", "format_version": 1, "phase": "...",
//! "amplitude": "...", "genome": {genome_to_json, outputs ["phase", "amplitude"]}}.
nlohmann::json controller_to_json(const Genome& controller);
//! Reads controller_to_json's object (or a bare genome object with two outputs): a lattice CPPN
//! only (a coevolved controller is one). Throws std::invalid_argument naming the field.
Genome controller_from_json(const nlohmann::json& json, double weight_range);

//! What a controller file holds: a lattice CPPN (five inputs, two outputs), or a HyperNEAT CPPN
//! (eight inputs, 2 + 2 outputs) and the substrate settings it paints.
struct ControllerProgram {
    Genome genome;
    std::optional<HyperNeatSettings> substrate;  //!< set for a HyperNEAT CPPN
};
//! controller_to_json's object for a HyperNEAT CPPN, with "substrate": {"radius", "steps",
//! "weight_threshold"} and the outputs named by the weights they paint.
nlohmann::json controller_to_json(const Genome& hyperneat_cppn, const HyperNeatSettings& substrate);
//! Reads either kind of controller file. Throws std::invalid_argument naming the field
//! ("controller.substrate.radius: ...").
ControllerProgram controller_program_from_json(const nlohmann::json& json, double weight_range);
//! Sets body.phase and body.amplitude from either kind: a HyperNEAT CPPN through its substrate
//! over body's lattice. Throws std::invalid_argument when that substrate would exceed
//! kMaxHyperNeatConnections (naming the body's lattice).
void paint_controller_program(const ControllerProgram& program,
                              const std::vector<MaterialEntry>& materials, Body& body);

}  // namespace bhm::evo
