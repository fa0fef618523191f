#pragma once
// One experiment file = one whole design problem (docs/experiment-format.md documents each field).
// Values are SI; voxel counts only where the field name says so.
#include <array>
#include <cstdint>
#include <optional>
#include <string>
#include <vector>

#include "engine/body_spec.hpp"

namespace bhm::evo {

enum class Face { XMin = 0, XMax, YMin, YMax, ZMin, ZMax };
inline constexpr std::array<const char*, 6> kFaceNames = {"x-", "x+", "y-", "y+", "z-", "z+"};

struct MaterialEntry {
    std::string name;
    engine::Material physics;
    std::array<float, 3> color{0.8f, 0.8f, 0.8f};  //!< RGB in [0, 1]
    bool has_color = false;
    //! The library material (assets/materials/<id>.json) the slot was filled from; "" = typed by
    //! hand. Provenance only once written: the file keeps every value (docs/materials-format.md).
    std::string library;
    //! cte > 0 under the sine model, a contraction strain > 0 under the muscle model
    bool active() const { return engine::is_active(physics); }
    bool operator==(const MaterialEntry&) const = default;
};

enum class PhaseMode { Uniform, Random };
inline constexpr std::array<const char*, 2> kPhaseNames = {"uniform", "random"};

struct ActuationSettings {
    double frequency_hz = 2.0;
    double temperature_amplitude_c = 14.47;
    PhaseMode phase = PhaseMode::Uniform;
    //! Added to every voxel's phase, in [-pi, pi]: a prototype's lag behind its drive, as
    //! bhm calibrate's phase_lag fits it (docs/calibration.md).
    double phase_offset_rad = 0.0;
    bool operator==(const ActuationSettings&) const = default;
};

enum class BoundaryKind { Free, Fixed };

enum class OverrideKind { Fixed, Empty, Material };
struct VoxelOverride {
    std::array<int, 3> voxel{0, 0, 0};
    OverrideKind kind = OverrideKind::Fixed;
    int material = 0;  //!< 1-based, for OverrideKind::Material
    bool operator==(const VoxelOverride&) const = default;
};

struct Boundary {
    std::array<BoundaryKind, 6> faces{};       //!< indexed by Face
    std::array<int, 6> enclosure_thickness{};  //!< voxels of passive frame per face
    int enclosure_material = 0;                //!< 1-based material index; 0 = none
    std::vector<VoxelOverride> voxel_overrides;
    bool any_fixed_face() const {
        for (auto f : faces)
            if (f == BoundaryKind::Fixed) return true;
        return false;
    }
    bool operator==(const Boundary&) const = default;
};

struct Simulation {
    double settle_s = 1.0;
    double evaluate_s = 10.0;
    double dt_fraction = 0.9;
    //! Each voxel's rotational inertia over a cube's (engine BodySpec::rotary_inertia_scale):
    //! above 1 the rotational modes slow and the stable step lengthens (issue 42,
    //! docs/benchmarks.md "the step size itself"). 1 (the default; a file without it) = the cube's.
    double rotary_inertia_scale = 1.0;
    double bond_damping_ratio = 1.0;
    double global_damping_ratio = 0.01;
    double collision_damping_ratio = 0.8;
    //! n > 0 (default 1): implicit bond damping, n sweeps, the zeta in full and a 2.2x longer
    //! stable step; 0: explicit (capped to stay stable at the step). Engine
    //! BodySpec::damping.implicit_sweeps; docs/physics.md.
    int implicit_damping_sweeps = 1;
    double record_fps = 30.0;
    //! End an evaluation once the motion repeats period by period and extrapolate the rest
    //! (evo/evaluate/periodic_end.hpp; docs/experiment-format.md).
    bool end_when_periodic = true;
    //! Allowed extrapolation error, relative to 1 voxel length (1 degree for the bend angle) plus
    //! the displacement the track reaches.
    double periodic_tolerance = 1e-3;
    bool operator==(const Simulation&) const = default;
};

enum class FitnessMeasure { ComFinal3d, ComFinalYz, ComMax3d, ComMaxYz, BendAngleDeg };
inline constexpr std::array<const char*, 5> kFitnessNames = {
    "com_final_3d", "com_final_yz", "com_max_3d", "com_max_yz", "bend_angle_deg"};

struct Constraints {
    bool attached_to_fixed_face = false;
    double min_fill_fraction = 0.0;
    int min_active_voxels = 0;
    //! Reject (fitness kInvalidFitness) bodies that raise an exploit flag
    //! (evo/evaluate/exploit_flags.hpp). escaped is known before simulating, so such bodies are
    //! never simulated.
    bool reject_escaped = false;
    bool reject_detached_motion = false;
    bool reject_tentacle = false;
    bool operator==(const Constraints&) const = default;
};

//! The body's volume (its filled voxel count) as an AFPO objective beside fitness and age
//! (docs/evolution.md, "Volume"): off, fewer voxels better (the trade-off of displacement and
//! volume: a smaller body that moves as far is better) or more voxels better.
enum class VolumeObjective { Off, Minimize, Maximize };
inline constexpr std::array<const char*, 3> kVolumeObjectiveNames = {"off", "minimize", "maximize"};

struct Fitness {
    FitnessMeasure measure = FitnessMeasure::ComFinal3d;
    Constraints constraints;
    bool minimize_active_voxels = false;                      //!< optional third AFPO objective
    VolumeObjective volume_objective = VolumeObjective::Off;  //!< optional volume objective
    bool operator==(const Fitness&) const = default;
};

//! How the CPPN's outputs pick a material: the paper's two outputs (present; active or passive,
//! the first material of each kind) or presence plus one output per material (argmax).
enum class MaterialOutputs { ActivePassive, PerMaterial };
inline constexpr std::array<const char*, 2> kMaterialOutputsNames = {"active_passive",
                                                                     "per_material"};

struct CppnSettings {
    int min_hidden_nodes = 4;  //!< paper Table 2: initial hidden nodes in [4, 10]
    int max_hidden_nodes = 10;
    double weight_range = 1.0;  //!< weights in [-range, range]
    double mutation_weight_sigma = 0.5;
    MaterialOutputs material_outputs = MaterialOutputs::ActivePassive;
    //! Three more outputs choose each muscle voxel's fibre axis (x, y or z: the largest of the
    //! three; evo/genome/cppn_decoder.hpp); off: every voxel has its material's muscle.fibre_axis.
    bool fibre_outputs = false;
    bool operator==(const CppnSettings&) const = default;
};

//! The evolutionary method (docs/evolution.md): the paper's AFPO, NEAT (Stanley & Miikkulainen
//! 2002) or novelty search (Lehman & Stanley 2011). EvolutionRun::run_generation dispatches on it.
//! "ga" (issue 44) is a plain generational genetic algorithm, the baseline of the controller
//! studies: tournament selection, elitism 1, mutation only or one-point crossover.
//! "hyperneat" (issue 44; docs/hyperneat.md): NEAT evolving a CPPN that paints the connection
//! weights of a substrate network over the voxel lattice, whose outputs paint the body or the
//! controller (evo/genome/hyperneat_substrate.hpp).
enum class Algorithm { Afpo, Neat, Novelty, Ga, HyperNeat };
inline constexpr std::array<const char*, 5> kAlgorithmNames = {"afpo", "neat", "novelty", "ga",
                                                               "hyperneat"};
//! NEAT's species and innovation history (evolution.neat) drive this algorithm.
inline bool uses_neat(Algorithm a) {
    return a == Algorithm::Neat || a == Algorithm::HyperNeat;
}

//! HyperNEAT's substrate (evolution.hyperneat; docs/hyperneat.md).
struct HyperNeatSettings {
    //! Local receptive field: node b receives from the nodes a with max(|dx|, |dy|, |dz|) <=
    //! radius lattice cells (itself included), so cells x (2 radius + 1)^3 connections at most.
    int radius = 1;
    int steps = 3;                  //!< activations of the hidden sheet before it is read
    double weight_threshold = 0.2;  //!< |CPPN output| below it: no connection (Stanley 2009)
    bool operator==(const HyperNeatSettings&) const = default;
};
//! The most substrate connections one sheet may have (cells x (2 radius + 1)^3): a CPPN query
//! each, per development.
inline constexpr double kMaxHyperNeatConnections = 2.0e6;

//! NEAT's parameters (evolution.neat; docs/evolution.md#neat). Defaults follow Stanley &
//! Miikkulainen 2002 where the paper gives one.
struct NeatSettings {
    double c1 = 1.0;  //!< compatibility distance: weight of excess genes
    double c2 = 1.0;  //!< ... of disjoint genes
    double c3 = 0.4;  //!< ... of the mean weight difference of matching genes
    //! Divide E and D by N, the larger genome's gene count, once either has 20 genes or more (the
    //! paper's normalisation). Off by default (N = 1): the step from 1 to 20 at 20 genes makes
    //! every large genome close to every other, so one species swallows the population.
    bool normalize_by_size = false;
    double compatibility_threshold = 3.0;  //!< delta below which a genome joins a species
    //! > 0: the threshold moves toward this many species (0: fixed). On by default: with CPPNs of
    //! 20 genes or more, N normalises E and D, and the paper's fixed 3 soon puts everyone in one
    //! species.
    int target_species = 5;
    double threshold_step = 0.3;      //!< how far the threshold moves per generation
    double survival_fraction = 0.2;   //!< best fraction of each species that may parent
    int elitism = 1;                  //!< best members of each species copied unchanged
    int stagnation_generations = 15;  //!< no improvement for this long: the species breeds no more
    double crossover_rate = 0.75;     //!< share of offspring made by crossover (then mutation)
    bool operator==(const NeatSettings&) const = default;
};

//! Novelty search (Lehman & Stanley 2011; evo/search/novelty.hpp, docs/evolution.md): used when the
//! algorithm is "novelty".
struct NoveltySettings {
    int k = 15;  //!< nearest behaviours averaged (Lehman & Stanley's 15)
    //! Novelty a new individual needs to enter the archive at the start (voxel lengths of
    //! behaviour distance); adapts every generation (evo/search/novelty_archive.hpp).
    double archive_threshold = 1.0;
    int archive_capacity = 1000;  //!< the oldest entries leave beyond this
    bool with_fitness = false;    //!< fitness as a second AFPO objective beside novelty
    bool operator==(const NoveltySettings&) const = default;
};

//! What a continuum check in the evolution loop does to a body it found out (docs/verify.md,
//! "CalculiX in the evolution loop"): flag records and shows it; penalise scales the fitness of a
//! body that differs beyond the tolerance by the FEM's static score over ours (at most 1); reject
//! makes such a body invalid, so it can be neither selected nor champion.
enum class VerifyPolicy { Flag, Penalise, Reject };
inline constexpr std::array<const char*, 3> kVerifyPolicyNames = {"flag", "penalise", "reject"};

//! evolution.verify: multi-fidelity evolution. After every `every_generations` generations the
//! `top_k` best distinct bodies not checked before are solved in CalculiX beside the next
//! generation's simulations; their results apply from that generation on.
struct LoopVerifySettings {
    int every_generations = 0;  //!< 0: no checks in the loop
    int top_k = 3;
    VerifyPolicy policy = VerifyPolicy::Flag;
    double tolerance = 0.10;  //!< largest relative difference that still agrees
    bool enabled() const { return every_generations > 0; }
    bool operator==(const LoopVerifySettings&) const = default;
};

//! A body: material index per lattice cell, x fastest, then y, then z (VoxCAD's VXC layers).
struct Body {
    std::array<int, 3> size{0, 0, 0};
    std::vector<std::uint8_t> cells;  //!< (nx*ny*nz) 0 = empty, k = materials[k-1]
    //! (nx*ny*nz) or empty: a muscle cell's own fibre axis, 0 = x, 1 = y, 2 = z, or
    //! engine::kMaterialFibreAxis (its material's muscle.fibre_axis); empty = all the material's.
    //! The body file's "fibres" (docs/experiment-format.md), the CPPN's fibre outputs.
    std::vector<std::uint8_t> fibre;
    //! (nx*ny*nz) or empty: a controller's actuation phase per cell in [-pi, pi] (issue 44; the
    //! body file's "controller"), in place of actuation.phase (phase_offset_rad still added);
    //! empty = the experiment's uniform or random phase.
    std::vector<float> phase;
    //! (nx*ny*nz) or empty: a controller's drive amplitude per cell in [0, 1]; empty = 1. Both are
    //! filled together (engine BodySpec::phase_rad, amplitude_scale).
    std::vector<float> amplitude;
    int cell_count() const { return size[0] * size[1] * size[2]; }
    int index(int x, int y, int z) const { return x + size[0] * (y + size[1] * z); }
    bool has_controller() const { return !phase.empty(); }
    bool operator==(const Body&) const = default;
};

//! evolution.controller (issue 44; docs/experiment-format.md, "Controllers"): what is evolved.
//! none: bodies, actuated by actuation.phase (as before); coevolve: each individual carries a body
//! CPPN and a controller CPPN, both mutate; fixed_body: only a controller, for `body`;
//! fixed_controllers: bodies, each evaluated under every one of `controllers`, fitness the mean.
enum class ControllerMode { None, Coevolve, FixedBody, FixedControllers };
inline constexpr std::array<const char*, 4> kControllerModeNames = {
    "none", "coevolve", "fixed_body", "fixed_controllers"};

//! One of fixed_controllers' set: a built-in ("uniform": phase 0; "random": phase uniform in
//! [-pi, pi) drawn from seed per cell; "wave": phase 2 pi x / length along x) at amplitude 1, or a
//! controller file's CPPN (genome: the file's JSON, checked by the genome reader).
struct ControllerEntry {
    std::string name;         //!< "uniform", "random", "wave", or the file it was read from
    std::uint64_t seed = 1;   //!< "random" only
    std::string genome_json;  //!< a controller file's genome (compact JSON); "" for a built-in
    bool operator==(const ControllerEntry&) const = default;
};

struct ControllerSettings {
    ControllerMode mode = ControllerMode::None;
    //! fixed_body: the body (as a body file holds it: the design or the framed workspace), kept
    //! with the experiment so that a resumed run has it; `bhm evolve E.json --body B.json` sets it.
    std::optional<Body> body;
    std::vector<ControllerEntry> controllers;  //!< fixed_controllers: at least one
    bool operator==(const ControllerSettings&) const = default;
};

struct Evolution {
    Algorithm algorithm = Algorithm::Afpo;
    int population = 50;
    int generations = 2000;
    double wall_budget_h = 48.0;
    int max_neutral_retries = 1500;
    std::uint64_t seed = 1;
    int threads = 0;  //!< 0 = all hardware threads
    //! Probability that a member's child is the crossover of it and a random mate
    //! (evo/search/crossover.hpp) before mutation is tried; 0 = the paper's mutation-only AFPO.
    double crossover_rate = 0.0;
    CppnSettings cppn;
    NeatSettings neat;            //!< used when algorithm is Neat or HyperNeat
    HyperNeatSettings hyperneat;  //!< used when algorithm is HyperNeat
    NoveltySettings novelty;
    LoopVerifySettings verify;
    ControllerSettings controller;
    bool operator==(const Evolution&) const = default;
};

struct Experiment {
    std::string name;
    std::string description;
    std::array<int, 3> workspace_size{8, 8, 7};
    double voxel_size_m = 0.01;
    std::vector<MaterialEntry> materials;
    ActuationSettings actuation;
    engine::Environment environment;
    Boundary boundary;
    Simulation simulation;
    Fitness fitness;
    Evolution evolution;
    bool operator==(const Experiment&) const = default;
};

}  // namespace bhm::evo
