// The field table (experiment_fields.hpp). Physics ranges are the engine's constants
// (engine/limits.hpp), so the editor, the validator and Model::build agree on them.
#include "evo/experiment/experiment_fields.hpp"

#include <cstdio>
#include <numbers>
#include <type_traits>

#include "engine/limits.hpp"
#include "engine/muscle.hpp"
#include "evo/experiment/field_rules.hpp"

namespace bhm::evo {

namespace {

namespace lim = engine::limits;
namespace mus = engine::muscle;
constexpr std::array<const char*, 2> kActuationModelNames = {"sine", "muscle"};
constexpr std::array<const char*, 3> kAxisNames = {"x", "y", "z"};
constexpr std::array<const char*, 2> kStimulusNames = {"pulse_train", "beating"};
constexpr bool kOpen = true;  // Range{lo, hi, kOpen}: lo excluded
// BoundaryKind's names in the file, in the enum's order.
constexpr std::array<const char*, 2> kBoundaryKindNames = {"free", "fixed"};

// One accessor per row, written as the member's path (MuJoCo's mjxmacro.h does the same). The
// rows are laid out by hand, a few designators a line, so the table reads as one.
// clang-format off
#define BHM_TEXT(expr) .text = [](Experiment& e) -> std::string& { return e.expr; }
#define BHM_NUMBER(expr) .number = [](Experiment& e) -> double& { return e.expr; }
#define BHM_INTEGER(expr) .integer = [](Experiment& e) -> int& { return e.expr; }
#define BHM_BOOLEAN(expr) .boolean = [](Experiment& e) -> bool& { return e.expr; }
#define BHM_CHOICE(expr, Enum, names)                                                 \
    .get_choice = [](const Experiment& e) { return static_cast<int>(e.expr); },      \
    .set_choice = [](Experiment& e, int v) { e.expr = static_cast<Enum>(v); }, \
    .choices = names
// One face of the workspace (kFaceNames[i] = name): held or free, and its frame's thickness.
#define BHM_FACE(i, name)                                                                  \
    {.path = "boundary.faces." name, .label = "Face " name, .unit = "",                   \
     .help = "fixed holds all six degrees of freedom of every voxel in the face layer",    \
     BHM_CHOICE(boundary.faces[i], BoundaryKind, kBoundaryKindNames)}
#define BHM_FRAME(i, name)                                                                 \
    {.path = "boundary.enclosure.thickness_voxels." name, .label = "Frame " name,         \
     .unit = "voxels", .help = "thickness of the passive frame (enclosure) on this face",  \
     .range = {0, kMaxWorkspaceDimension}, BHM_INTEGER(boundary.enclosure_thickness[i])}
#define BHM_MATERIAL(member) .number = [](engine::Material& m) -> double& { return m.member; }
#define BHM_MATERIAL_CHOICE(member, Enum, names)                                           \
    .get_choice = [](const engine::Material& m) { return static_cast<int>(m.member); },   \
    .set_choice = [](engine::Material& m, int v) { m.member = static_cast<Enum>(v); },    \
    .choices = names

const ExperimentField kExperimentFields[] = {
    {.path = "name", .label = "##name", .unit = "", .help = "experiment name",
     BHM_TEXT(name)},
    {.path = "description", .label = "##description", .unit = "",
     .help = "description: the problem and sources", BHM_TEXT(description)},
    {.path = "workspace.size", .label = "Workspace", .unit = "voxels",
     .help = "lattice size (x, y, z); paper exp. 3: 20 x 8 x 7",
     .range = {1, kMaxWorkspaceDimension},
     .size3 = [](Experiment& e) -> std::array<int, 3>& { return e.workspace_size; }},
    {.path = "workspace.voxel_size_m", .label = "Voxel size", .unit = "m",
     .help = "edge length of one voxel; paper: 0.01 m",
     .range = {lim::kMinVoxelSizeM, lim::kMaxVoxelSizeM}, .format = "%.6g",
     BHM_NUMBER(voxel_size_m)},
    {.path = "actuation.frequency_hz", .label = "Frequency", .unit = "Hz",
     .help = "actuation frequency; paper Table 1: 2 Hz", .range = {0, lim::kMaxFrequencyHz},
     BHM_NUMBER(actuation.frequency_hz)},
    {.path = "actuation.temperature_amplitude_c", .label = "Amplitude", .unit = "degC",
     .help = "temperature swing of the active material; Kriegman 2020: 14.47",
     .range = {0, lim::kMaxTemperatureAmplitudeC},
     BHM_NUMBER(actuation.temperature_amplitude_c)},
    {.path = "actuation.phase", .label = "Phase", .unit = "",
     .help = "per-voxel phase: uniform (all 0) or random (drawn per voxel)",
     BHM_CHOICE(actuation.phase, PhaseMode, kPhaseNames)},
    {.path = "actuation.phase_offset_rad", .label = "Phase offset", .unit = "rad",
     .help = "added to every voxel's phase: a prototype's lag behind its drive (bhm calibrate's "
             "phase_lag)",
     .range = {-std::numbers::pi, std::numbers::pi}, BHM_NUMBER(actuation.phase_offset_rad)},
    {.path = "environment.gravity_m_s2", .label = "Gravity", .unit = "m/s^2",
     .help = "along z; -9.81 pulls down", .range = {-lim::kMaxGravityMS2, lim::kMaxGravityMS2},
     BHM_NUMBER(environment.gravity_m_s2)},
    {.path = "environment.floor", .label = "Floor at z = 0", .unit = "",
     .help = "penalty contact with Coulomb friction", BHM_BOOLEAN(environment.floor)},
    BHM_FACE(0, "x-"), BHM_FACE(1, "x+"), BHM_FACE(2, "y-"),
    BHM_FACE(3, "y+"), BHM_FACE(4, "z-"), BHM_FACE(5, "z+"),
    BHM_FRAME(0, "x-"), BHM_FRAME(1, "x+"), BHM_FRAME(2, "y-"),
    BHM_FRAME(3, "y+"), BHM_FRAME(4, "z-"), BHM_FRAME(5, "z+"),
    {.path = "boundary.enclosure.material", .label = "Frame material", .unit = "",
     .help = "the frame's material, 1-based (paper section 4.3)", .range = {0, kMaxMaterials},
     .note = "(0 = none)", BHM_INTEGER(boundary.enclosure_material)},
    {.path = "simulation.settle_s", .label = "Settle", .unit = "s",
     .help = "gravity only, actuation off; paper: 1 s", .range = {0, 1e4},
     BHM_NUMBER(simulation.settle_s)},
    {.path = "simulation.evaluate_s", .label = "Evaluate", .unit = "s",
     .help = "actuated time; paper: 10 s", .range = {0, 1e5, kOpen},
     BHM_NUMBER(simulation.evaluate_s)},
    {.path = "simulation.dt_fraction", .label = "dt fraction", .unit = "",
     .help = "time step as a fraction of the stable step; past 1 only with the implicit damping "
             "(presets: 1.2 with rotary inertia scale 1.5, docs/benchmarks.md)",
     .range = {0, lim::kMaxDtFraction, kOpen}, .note = "(a fraction of the stable step)",
     .format = "%.3f", BHM_NUMBER(simulation.dt_fraction)},
    {.path = "simulation.rotary_inertia_scale", .label = "Rotary inertia scale", .unit = "",
     .help = "each voxel's rotational inertia over a cube's m L^2 / 6; above 1 the rotational "
             "modes slow and the stable step lengthens (up to 1.19x at 1.5, docs/benchmarks.md)",
     .range = {lim::kMinRotaryInertiaScale, lim::kMaxRotaryInertiaScale},
     .note = "(1 = a solid cube's)", .format = "%.3g",
     BHM_NUMBER(simulation.rotary_inertia_scale)},
    {.path = "simulation.bond_damping_ratio", .label = "Bond damping", .unit = "",
     .help = "damping of each link, as a ratio of critical (Voxelyze zeta_internal); 1",
     .range = {0, lim::kMaxDampingRatio}, .format = "%.3f",
     BHM_NUMBER(simulation.bond_damping_ratio)},
    {.path = "simulation.global_damping_ratio", .label = "Global damping", .unit = "",
     .help = "damping of each voxel toward rest, as a ratio of critical (zeta_global)",
     .range = {0, lim::kMaxDampingRatio}, .format = "%.3f",
     BHM_NUMBER(simulation.global_damping_ratio)},
    {.path = "simulation.collision_damping_ratio", .label = "Collision damping", .unit = "",
     .help = "damping of floor contact, as a ratio of critical", .range = {0, lim::kMaxDampingRatio},
     .format = "%.3f", BHM_NUMBER(simulation.collision_damping_ratio)},
    {.path = "simulation.implicit_damping_sweeps", .label = "Implicit damping sweeps", .unit = "",
     .help = "1 (default): implicit bond damping, the full zeta and a 2.2x longer stable step; "
             "n > 1: more sweeps; 0: explicit, capped at the step (docs/physics.md)",
     .range = {0, lim::kMaxImplicitSweeps}, BHM_INTEGER(simulation.implicit_damping_sweeps)},
    {.path = "simulation.record_fps", .label = "Record rate", .unit = "frames/s",
     .help = "replay frames and fitness samples per second", .range = {0, 1000, kOpen},
     BHM_NUMBER(simulation.record_fps)},
    {.path = "simulation.end_when_periodic", .label = "End when periodic", .unit = "",
     .help = "end an evaluation once the motion repeats period by period; extrapolate the rest",
     BHM_BOOLEAN(simulation.end_when_periodic)},
    {.path = "simulation.periodic_tolerance", .label = "Periodic tolerance", .unit = "",
     .help = "allowed extrapolation error, relative to 1 voxel length (1 deg for the bend angle) "
             "plus the displacement reached",
     .range = {0, 1, kOpen}, .format = "%.3g", BHM_NUMBER(simulation.periodic_tolerance)},
    {.path = "fitness.measure", .label = "Measure", .unit = "",
     .help = "what evolution maximises: centre-of-mass travel (voxel lengths) or bend angle (deg)",
     BHM_CHOICE(fitness.measure, FitnessMeasure, kFitnessNames)},
    {.path = "fitness.minimize_active_voxels", .label = "Minimise active voxels", .unit = "",
     .help = "third AFPO objective", BHM_BOOLEAN(fitness.minimize_active_voxels)},
    {.path = "fitness.volume_objective", .label = "Volume objective", .unit = "",
     .help = "the body's voxel count as an AFPO objective: off, minimize (a smaller body that "
             "moves as far is better) or maximize",
     BHM_CHOICE(fitness.volume_objective, VolumeObjective, kVolumeObjectiveNames)},
    {.path = "fitness.constraints.attached_to_fixed_face", .label = "Attached to fixed face",
     .unit = "", .help = "the body must touch every fixed face (paper section 4.1)",
     BHM_BOOLEAN(fitness.constraints.attached_to_fixed_face)},
    {.path = "fitness.constraints.min_fill_fraction", .label = "Min fill", .unit = "",
     .help = "share of the design space the body must fill", .range = {0, 1}, .format = "%.3f",
     BHM_NUMBER(fitness.constraints.min_fill_fraction)},
    {.path = "fitness.constraints.min_active_voxels", .label = "Min active", .unit = "voxels",
     .help = "active voxels a body needs", .range = {0, kMaxWorkspaceCells},
     BHM_INTEGER(fitness.constraints.min_active_voxels)},
    {.path = "fitness.constraints.reject_escaped", .label = "escaped (E)", .unit = "",
     .help = "reject voxels not held by a fixed face, directly or through neighbours; checked "
             "before simulating, so such bodies are never simulated",
     BHM_BOOLEAN(fitness.constraints.reject_escaped)},
    {.path = "fitness.constraints.reject_detached_motion", .label = "detached motion (D)",
     .unit = "",
     .help = "reject a body that moves while its part next to the fixed face barely does; "
             "scored -2",
     BHM_BOOLEAN(fitness.constraints.reject_detached_motion)},
    {.path = "fitness.constraints.reject_tentacle", .label = "tentacle (T)", .unit = "",
     .help = "reject a body whose thin voxels (at most 2 filled neighbours) carry most of the "
             "motion; scored -2",
     BHM_BOOLEAN(fitness.constraints.reject_tentacle)},
    {.path = "evolution.algorithm", .label = "Algorithm", .unit = "",
     .help = "AFPO (the paper's), NEAT, novelty search, a plain generational GA "
             "(docs/evolution.md) or HyperNEAT (docs/hyperneat.md)",
     BHM_CHOICE(evolution.algorithm, Algorithm, kAlgorithmNames)},
    {.path = "evolution.controller.mode", .label = "Controller", .unit = "",
     .help = "what evolves (docs/experiment-format.md, Controllers): none = bodies under "
             "actuation.phase; coevolve = body and controller CPPNs; fixed_body = a controller "
             "for controller.body; fixed_controllers = bodies, fitness the mean over "
             "controller.controllers",
     BHM_CHOICE(evolution.controller.mode, ControllerMode, kControllerModeNames)},
    {.path = "evolution.population", .label = "Population", .unit = "",
     .help = "individuals per generation; paper: 50", .range = {2, 100000},
     BHM_INTEGER(evolution.population)},
    {.path = "evolution.generations", .label = "Generations", .unit = "",
     .help = "generations to run; paper: 2000", .range = {0, 1e8},
     BHM_INTEGER(evolution.generations)},
    {.path = "evolution.wall_budget_h", .label = "Wall budget", .unit = "h",
     .help = "the run stops after this wall time; paper: 48 h", .range = {0, 1e5, kOpen},
     BHM_NUMBER(evolution.wall_budget_h)},
    {.path = "evolution.max_neutral_retries", .label = "Neutral retries", .unit = "",
     .help = "mutation retries for an identical or invalid child", .range = {0, 1e7},
     BHM_INTEGER(evolution.max_neutral_retries)},
    {.path = "evolution.seed", .label = "Seed", .unit = "", .help = "the run's random seed",
     .seed = [](Experiment& e) -> std::uint64_t& { return e.evolution.seed; }},
    {.path = "evolution.threads", .label = "Threads", .unit = "",
     .help = "evaluation threads", .range = {0, 1024}, .note = "(0 = all cores)",
     BHM_INTEGER(evolution.threads)},
    {.path = "evolution.crossover_rate", .label = "Crossover rate", .unit = "",
     .help = "share of AFPO children made by crossover before mutation", .range = {0, 1},
     .note = "(0 = mutation only, the paper's)", .format = "%.3g",
     BHM_NUMBER(evolution.crossover_rate)},
    {.path = "evolution.cppn.min_hidden_nodes", .label = "CPPN min hidden", .unit = "nodes",
     .help = "fewest hidden nodes of a new CPPN; paper Table 2: 4", .range = {0, 1000},
     BHM_INTEGER(evolution.cppn.min_hidden_nodes)},
    {.path = "evolution.cppn.max_hidden_nodes", .label = "CPPN max hidden", .unit = "nodes",
     .help = "most hidden nodes of a new CPPN; paper Table 2: 10", .range = {0, 1000},
     BHM_INTEGER(evolution.cppn.max_hidden_nodes)},
    {.path = "evolution.cppn.weight_range", .label = "Weight range", .unit = "",
     .help = "CPPN weights lie in [-range, range]; paper: 1", .range = {0, 100, kOpen},
     .format = "%.3g", BHM_NUMBER(evolution.cppn.weight_range)},
    {.path = "evolution.cppn.mutation_weight_sigma", .label = "Weight sigma", .unit = "",
     .help = "standard deviation of a weight mutation", .range = {0, 100, kOpen},
     .format = "%.3g", BHM_NUMBER(evolution.cppn.mutation_weight_sigma)},
    {.path = "evolution.cppn.material_outputs", .label = "Material outputs", .unit = "",
     .help = "how the CPPN picks a material: active or passive (the paper's two outputs), or "
             "one output per material",
     BHM_CHOICE(evolution.cppn.material_outputs, MaterialOutputs, kMaterialOutputsNames)},
    {.path = "evolution.cppn.fibre_outputs", .label = "Fibre outputs", .unit = "",
     .help = "three more CPPN outputs choose each muscle voxel's fibre axis (the largest of "
             "x, y, z); off: every voxel has its material's fibre axis",
     BHM_BOOLEAN(evolution.cppn.fibre_outputs)},
    {.path = "evolution.hyperneat.radius", .label = "Receptive field", .unit = "voxels",
     .help = "HyperNEAT: a substrate node receives from the nodes within this many voxels on "
             "every axis (itself included; docs/hyperneat.md)",
     .range = {1, 4}, BHM_INTEGER(evolution.hyperneat.radius)},
    {.path = "evolution.hyperneat.steps", .label = "Substrate steps", .unit = "",
     .help = "HyperNEAT: activations of the substrate's hidden sheet before the outputs read it",
     .range = {1, 50}, BHM_INTEGER(evolution.hyperneat.steps)},
    {.path = "evolution.hyperneat.weight_threshold", .label = "Weight threshold", .unit = "",
     .help = "HyperNEAT: a CPPN output of smaller magnitude expresses no connection",
     .range = {0, 100}, .format = "%.3g", BHM_NUMBER(evolution.hyperneat.weight_threshold)},
    {.path = "evolution.neat.c1", .label = "NEAT c1", .unit = "",
     .help = "compatibility distance: weight of excess genes", .range = {0, 100},
     .format = "%.3g", BHM_NUMBER(evolution.neat.c1)},
    {.path = "evolution.neat.c2", .label = "NEAT c2", .unit = "",
     .help = "compatibility distance: weight of disjoint genes", .range = {0, 100},
     .format = "%.3g", BHM_NUMBER(evolution.neat.c2)},
    {.path = "evolution.neat.c3", .label = "NEAT c3", .unit = "",
     .help = "compatibility distance: weight of the mean weight difference", .range = {0, 100},
     .format = "%.3g", BHM_NUMBER(evolution.neat.c3)},
    {.path = "evolution.neat.normalize_by_size", .label = "NEAT divide by N", .unit = "",
     .help = "divide E and D by the larger gene count from 20 genes on (the paper's)",
     BHM_BOOLEAN(evolution.neat.normalize_by_size)},
    {.path = "evolution.neat.compatibility_threshold", .label = "Compat. threshold", .unit = "",
     .help = "closer than this to a species' representative joins the species",
     .range = {0, 1000, kOpen}, .format = "%.3g",
     BHM_NUMBER(evolution.neat.compatibility_threshold)},
    {.path = "evolution.neat.target_species", .label = "Target species", .unit = "",
     .help = "the threshold moves toward this many species", .range = {0, 100000},
     .note = "(0 = keep the threshold fixed)", BHM_INTEGER(evolution.neat.target_species)},
    {.path = "evolution.neat.threshold_step", .label = "Threshold step", .unit = "",
     .help = "how far the threshold moves per generation", .range = {0, 100, kOpen},
     .format = "%.3g", BHM_NUMBER(evolution.neat.threshold_step)},
    {.path = "evolution.neat.survival_fraction", .label = "Survival", .unit = "",
     .help = "best share of each species that may parent", .range = {0, 1, kOpen},
     .format = "%.3g", BHM_NUMBER(evolution.neat.survival_fraction)},
    {.path = "evolution.neat.elitism", .label = "Elitism", .unit = "",
     .help = "best members of each species copied unchanged", .range = {0, 100000},
     BHM_INTEGER(evolution.neat.elitism)},
    {.path = "evolution.neat.stagnation_generations", .label = "Stagnation", .unit = "generations",
     .help = "no improvement for this long: the species breeds no more", .range = {1, 1e8},
     BHM_INTEGER(evolution.neat.stagnation_generations)},
    {.path = "evolution.neat.crossover_rate", .label = "NEAT crossover", .unit = "",
     .help = "share of offspring made by crossover (then mutation)", .range = {0, 1},
     .format = "%.3g", BHM_NUMBER(evolution.neat.crossover_rate)},
    {.path = "evolution.novelty.k", .label = "Novelty k", .unit = "",
     .help = "nearest behaviours averaged (Lehman & Stanley's 15)", .range = {1, 1000},
     BHM_INTEGER(evolution.novelty.k)},
    {.path = "evolution.novelty.archive_threshold", .label = "Archive threshold",
     .unit = "voxel lengths",
     .help = "novelty a new individual needs to enter the archive at the start; adapts",
     .range = {0, 1e6, kOpen}, .format = "%.3g", BHM_NUMBER(evolution.novelty.archive_threshold)},
    {.path = "evolution.novelty.archive_capacity", .label = "Archive capacity", .unit = "",
     .help = "the oldest entries leave beyond this", .range = {0, 100000},
     BHM_INTEGER(evolution.novelty.archive_capacity)},
    {.path = "evolution.novelty.with_fitness", .label = "With fitness", .unit = "",
     .help = "fitness as a second objective beside novelty (finds better benders)",
     BHM_BOOLEAN(evolution.novelty.with_fitness)},
    {.path = "evolution.verify.every_generations", .label = "Verify every", .unit = "generations",
     .help = "solve the best bodies in CalculiX after every this many generations, beside the "
             "next generation's simulations (docs/verify.md)",
     .range = {0, 1e8}, .note = "(0 = off)", BHM_INTEGER(evolution.verify.every_generations)},
    {.path = "evolution.verify.top_k", .label = "Verify top K", .unit = "bodies",
     .help = "best distinct bodies checked each time (those checked before are skipped)",
     .range = {1, 1000}, BHM_INTEGER(evolution.verify.top_k)},
    {.path = "evolution.verify.policy", .label = "Verify policy", .unit = "",
     .help = "flag: record and show; penalise: a body that differs has its fitness times the "
             "FEM's static score over ours (at most 1); reject: a body that differs beyond the "
             "tolerance is invalid",
     BHM_CHOICE(evolution.verify.policy, VerifyPolicy, kVerifyPolicyNames)},
    {.path = "evolution.verify.tolerance", .label = "Verify tolerance", .unit = "",
     .help = "largest relative difference from the FEM that still agrees; 0.1 = 10 %",
     .range = {0, 10, kOpen}, .format = "%.3g", BHM_NUMBER(evolution.verify.tolerance)},
};

const MaterialField kMaterialFields[] = {
    {.path = "youngs_modulus_pa", .label = "E", .unit = "Pa",
     .help = "Young's modulus; paper Table 1: 5e6",
     .range = {0, lim::kMaxYoungsModulusPa, kOpen}, .note = "(beyond any real material)",
     BHM_MATERIAL(youngs_modulus_pa)},
    {.path = "density_kg_m3", .label = "Density", .unit = "kg/m^3", .help = "paper: 1000",
     .range = {0, lim::kMaxDensityKgM3, kOpen}, BHM_MATERIAL(density_kg_m3)},
    {.path = "poisson_ratio", .label = "Poisson", .unit = "", .help = "paper: 0.35",
     .range = {lim::kMinPoissonRatio, lim::kMaxPoissonRatio},
     .note = "(the engine's validated range)", .format = "%.3f", BHM_MATERIAL(poisson_ratio)},
    {.path = "cte_per_c", .label = "CTE", .unit = "1/degC",
     .help = "linear thermal expansion; > 0 makes the material active (muscle); paper: 0.01",
     .range = {0, 1}, .note = "(> 0 makes the material active)",
     BHM_MATERIAL(cte_per_c)},
    {.path = "static_friction", .label = "Static friction", .unit = "",
     .help = "Coulomb friction against the floor; paper: 1", .range = {0}, .format = "%.3f",
     BHM_MATERIAL(static_friction)},
    {.path = "dynamic_friction", .label = "Dynamic friction", .unit = "",
     .help = "Coulomb friction against the floor while sliding; paper: 0.5", .range = {0},
     .format = "%.3f",
     BHM_MATERIAL(dynamic_friction)},
    {.path = "actuation_model", .label = "Actuation model", .unit = "",
     .help = "how an active material is driven: sine (the paper's thermal expansion, cte x "
             "amplitude sin(2 pi f t)) or muscle (contraction along fibres, twitch dynamics; "
             "the muscle fields below)",
     BHM_MATERIAL_CHOICE(actuation_model, engine::ActuationModel, kActuationModelNames)},
    {.path = "muscle.fibre_axis", .label = "Fibre axis", .unit = "",
     .help = "muscle: the lattice axis its fibres run along; it contracts along it and "
             "thickens across by Poisson's ratio",
     BHM_MATERIAL_CHOICE(muscle.fibre_axis, int, kAxisNames)},
    {.path = "muscle.contraction_strain", .label = "Contraction strain", .unit = "",
     .help = "muscle: free shortening along the fibres at full (tetanic) activation; > 0 makes "
             "the material active",
     .range = {0, mus::kMaxContractionStrain}, .note = "(the engine's stable actuation strain)",
     .format = "%.4f", BHM_MATERIAL(muscle.contraction_strain)},
    {.path = "muscle.rise_s", .label = "Activation time", .unit = "s",
     .help = "muscle: time constant of the activation's rise while stimulated (a twitch's "
             "contraction phase)",
     .range = {mus::kMinTimeConstantS, mus::kMaxTimeConstantS}, BHM_MATERIAL(muscle.rise_s)},
    {.path = "muscle.decay_s", .label = "Relaxation time", .unit = "s",
     .help = "muscle: time constant of the activation's decay between stimuli (a twitch's "
             "relaxation)",
     .range = {mus::kMinTimeConstantS, mus::kMaxTimeConstantS}, BHM_MATERIAL(muscle.decay_s)},
    {.path = "muscle.stimulus", .label = "Stimulus", .unit = "",
     .help = "muscle: pulse_train (electrical or optical pacing, optional on/off schedule) or "
             "beating (spontaneous, cardiomyocytes)",
     BHM_MATERIAL_CHOICE(muscle.stimulus, engine::MuscleStimulus, kStimulusNames)},
    {.path = "muscle.frequency_hz", .label = "Pulse / beat rate", .unit = "Hz",
     .help = "muscle: pulses (or beats) per second; fast trains fuse twitches into tetanus",
     .range = {0, mus::kMaxStimulusFrequencyHz, kOpen}, BHM_MATERIAL(muscle.frequency_hz)},
    {.path = "muscle.pulse_width_s", .label = "Pulse width", .unit = "s",
     .help = "muscle: how long each pulse excites the tissue; twitch peak / tetanus = "
             "1 - exp(-width / activation time)",
     .range = {0, mus::kMaxTimeConstantS, kOpen}, BHM_MATERIAL(muscle.pulse_width_s)},
    {.path = "muscle.train_on_s", .label = "Burst length", .unit = "s",
     .help = "muscle pulse train: length of a burst of pulses; 0 = one endless train",
     .range = {0, mus::kMaxTrainS}, .note = "(0 = endless)", BHM_MATERIAL(muscle.train_on_s)},
    {.path = "muscle.train_off_s", .label = "Rest between bursts", .unit = "s",
     .help = "muscle pulse train: rest between bursts; 0 = one endless train",
     .range = {0, mus::kMaxTrainS}, .note = "(0 = endless)", BHM_MATERIAL(muscle.train_off_s)},
    {.path = "muscle.fatigue_s", .label = "Fatigue time", .unit = "s",
     .help = "muscle: time constant of the force's loss while stimulated, toward the fatigue "
             "floor (the force left is f, df/dt = -(f - floor) / fatigue time); 0 = no fatigue",
     .range = {0, mus::kMaxFatigueS}, .note = "(0 = no fatigue)", BHM_MATERIAL(muscle.fatigue_s)},
    {.path = "muscle.recovery_s", .label = "Recovery time", .unit = "s",
     .help = "muscle with fatigue: time constant of the force's recovery at rest "
             "(df/dt = (1 - f) / recovery time); needed when the fatigue time is > 0",
     .range = {0, mus::kMaxFatigueS}, .note = "(> 0 with fatigue)",
     BHM_MATERIAL(muscle.recovery_s)},
    {.path = "muscle.fatigue_floor", .label = "Fatigue floor", .unit = "",
     .help = "muscle with fatigue: the fraction of its force a long stimulus leaves it; 1 = none "
             "lost",
     .range = {0, 1}, .format = "%.3f", BHM_MATERIAL(muscle.fatigue_floor)},
};

// clang-format on

#undef BHM_TEXT
#undef BHM_NUMBER
#undef BHM_INTEGER
#undef BHM_BOOLEAN
#undef BHM_CHOICE
#undef BHM_FACE
#undef BHM_FRAME
#undef BHM_MATERIAL
#undef BHM_MATERIAL_CHOICE

std::string printed(const char* format, double x) {
    char buf[48];
    std::snprintf(buf, sizeof buf, format, x);
    return buf;
}

}  // namespace

std::span<const ExperimentField> experiment_fields() {
    return kExperimentFields;
}

std::span<const MaterialField> material_fields() {
    return kMaterialFields;
}

const ExperimentField* find_experiment_field(std::string_view path) {
    for (const auto& f : kExperimentFields)
        if (path == f.path) return &f;
    return nullptr;
}

const MaterialField* find_material_field(std::string_view key) {
    for (const auto& f : kMaterialFields)
        if (key == f.path) return &f;
    return nullptr;
}

std::string range_number(double x) {
    if (std::isinf(x)) return x > 0 ? "inf" : "-inf";
    if (x == std::floor(x) && std::fabs(x) < 1e6) return printed("%.0f", x);
    // %g, with the exponent as a person writes it: 1e+06 -> 1e6, 1e-06 -> 1e-6.
    std::string s = printed("%g", x);
    const auto e = s.find('e');
    if (e == std::string::npos) return s;
    std::string mantissa = s.substr(0, e), exponent = s.substr(e + 1);
    const bool negative = exponent[0] == '-';
    exponent.erase(0, exponent.find_first_not_of("+-0"));
    return mantissa + "e" + (negative ? "-" : "") + exponent;
}

std::string range_text(const Range& r) {
    const bool lo_open = r.lo_open || std::isinf(r.lo), hi_open = r.hi_open || std::isinf(r.hi);
    return std::string(lo_open ? "(" : "[") + range_number(r.lo) + ", " + range_number(r.hi) +
           (hi_open ? ")" : "]");
}

template <class Host>
std::string range_message(const FieldOf<Host>& f) {
    std::string s = "must be in " + range_text(f.range);
    if (*f.unit) s += std::string(" ") + f.unit;
    if (*f.note) s += std::string(" ") + f.note;
    return s;
}

template <class Host>
std::string field_value_text(const FieldOf<Host>& f, const Host& host) {
    Host& h = const_cast<Host&>(host);  // the accessors are shared with writers; read only here
    switch (f.kind()) {
        case FieldKind::Text:
            return f.text(h);
        case FieldKind::Number:
            return printed("%g", f.number(h));
        case FieldKind::Integer:
            return std::to_string(f.integer(h));
        case FieldKind::Boolean:
            return f.boolean(h) ? "true" : "false";
        case FieldKind::Choice:
            return f.choices[static_cast<std::size_t>(f.get_choice(h))];
        case FieldKind::Seed:
            return std::to_string(f.seed(h));
        case FieldKind::Size3: {
            const auto& v = f.size3(h);
            return "[" + std::to_string(v[0]) + ", " + std::to_string(v[1]) + ", " +
                   std::to_string(v[2]) + "]";
        }
    }
    return "";
}

// How field_rules.hpp names a field of Host: materials' fields as "materials[].<key>".
template <class Host>
constexpr const char* rule_prefix() {
    return std::is_same_v<Host, engine::Material> ? "materials[]." : "";
}

template <class Host>
std::string field_tooltip(const FieldOf<Host>& f) {
    std::string s = f.help;
    std::string line;
    const FieldKind kind = f.kind();
    if (kind == FieldKind::Number || kind == FieldKind::Integer || kind == FieldKind::Size3) {
        line = range_text(f.range);
        if (*f.unit) line += std::string(" ") + f.unit;
        if (*f.note) line += std::string(" ") + f.note;
    } else if (kind == FieldKind::Choice) {
        line = "one of";
        for (std::size_t k = 0; k < f.choices.size(); ++k)
            line += std::string(k ? ", " : " ") + f.choices[k];
    }
    const std::string rules = rules_text(std::string(rule_prefix<Host>()) + f.path);
    if (!rules.empty()) line += (line.empty() ? "" : "; ") + rules;
    if (kind != FieldKind::Text) {
        const Host defaults{};
        line += (line.empty() ? "default " : "; default ") + field_value_text(f, defaults);
    }
    return line.empty() ? s : s + "\n" + line;
}

template std::string range_message(const ExperimentField&);
template std::string range_message(const MaterialField&);
template std::string field_value_text(const ExperimentField&, const Experiment&);
template std::string field_value_text(const MaterialField&, const engine::Material&);
template std::string field_tooltip(const ExperimentField&);
template std::string field_tooltip(const MaterialField&);

}  // namespace bhm::evo
