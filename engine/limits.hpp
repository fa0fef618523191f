#pragma once
// The engine's physics envelope: the one place that says which inputs the engine can simulate and
// how many steps a simulation needs. Model::build refuses exactly what these functions refuse, and
// evo/ (experiment validation, hence `bhm validate`, `simulate` and `evolve`) calls the same
// functions, so a document that validates always runs. docs/physics.md explains each bound.
#include <cstdint>
#include <string>
#include <vector>

#include "engine/body_spec.hpp"

namespace bhm::engine::limits {

inline constexpr double kMinVoxelSizeM = 1e-6;
inline constexpr double kMaxVoxelSizeM = 10.0;
inline constexpr double kMaxYoungsModulusPa = 1e12;  //!< beyond diamond
inline constexpr double kMaxDensityKgM3 = 1e6;       //!< 40x osmium
inline constexpr double kMinPoissonRatio = -0.9;     //!< inclusive; -1 makes G infinite
inline constexpr double kMaxPoissonRatio = 0.49;     //!< inclusive; 0.5 is incompressible
//! Largest |cte x temperature amplitude| (linear actuation strain) the engine runs stably on the
//! paper's scenes at the default damping and dt_fraction (tests/engine/test_engine_envelope.cpp;
//! measured: all three survive 0.6, the banded block diverges at 0.65).
inline constexpr double kMaxActuationStrain = 0.6;
//! dt_fraction with the implicit bond damping (the default): up to 1.6 of kImplicitStepMultiple,
//! the envelope fuzz's 600 random bodies stable with their drawn fractions stretched to reach it
//! (issue 42, docs/benchmarks.md "a longer step"); the presets run below it.
inline constexpr double kMaxDtFraction = 1.6;
//! dt_fraction with the explicit bond damping (implicit_sweeps 0): Voxelyze's own step at most
//! (the pulled bar blows up at 1.26x it, docs/physics.md).
inline constexpr double kMaxExplicitDtFraction = 1.0;
//! BodySpec::rotary_inertia_scale: at least a cube's own inertia (less would only shorten the
//! step), at most 100x (issue 42: S 4 already moves free walkers by 0.3-0.5 % of their swing).
inline constexpr double kMinRotaryInertiaScale = 1.0;
inline constexpr double kMaxRotaryInertiaScale = 100.0;
inline constexpr double kMaxFrequencyHz = 1000.0;
inline constexpr double kMaxTemperatureAmplitudeC = 1000.0;
inline constexpr double kMaxGravityMS2 = 1000.0;  //!< |gravity| along z
inline constexpr double kMaxDampingRatio = 10.0;
//! Jacobi sweeps of the implicit bond damping (BodySpec::damping.implicit_sweeps)
inline constexpr int kMaxImplicitSweeps = 16;
//! With the implicit bond damping the largest stable step is this multiple of Voxelyze's
//! 1 / (2 pi omega_max) (with the explicit damping: 1): the paper's scenes, the corpus and the
//! envelope's random bodies are all stable at 1.36x this, and at dt_fraction 0.9 the accuracy
//! gate holds (docs/physics.md, "Damping and the step").
inline constexpr double kImplicitStepMultiple = 2.2;
//! A simulation needing more steps than this is refused (hours of wall time per simulation).
inline constexpr double kMaxStepsPerSimulation = 1e8;
//! Fewest steps a simulation may take, and fewest per actuation period (a sine sampled coarser
//! than this is no longer the prescribed actuation).
inline constexpr double kMinStepsPerSimulation = 100.0;
inline constexpr double kMinStepsPerActuationPeriod = 20.0;
//! Nominal single-thread engine throughput, only for the "about N h" of a refusal message
//! (docs/benchmarks.md: 43-49 M voxel-steps/s on the 2-core CI machine class).
inline constexpr double kNominalVoxelStepsPerS = 4e7;

//! One input the engine cannot run: the field (relative to the object checked, as in BodySpec,
//! e.g. "youngs_modulus_pa") and a one-line reason.
struct Problem {
    std::string field;
    std::string message;
};

//! Problems of one material; temperature_amplitude_c bounds the actuation strain cte x A.
std::vector<Problem> material_problems(const Material& m, double temperature_amplitude_c);
//! Problems of the voxel size, damping ratios, dt_fraction, actuation and gravity (fields named
//! as in BodySpec: "voxel_size_m", "damping.bond_ratio", "dt_fraction", ...).
std::vector<Problem> settings_problems(const BodySpec& spec);
//! Every problem of a whole BodySpec: sizes, materials, settings, an empty body.
std::vector<Problem> body_spec_problems(const BodySpec& spec);

//! Squared angular frequency of the stiffest mode of a lone voxel of material m (rad^2/s^2), at
//! its largest actuated size s = 1 + |cte A| (axial stiffness ~ s, bending and torsion ~ s^2).
//! rotary_inertia_scale: the voxels' rotational inertia over a cube's (BodySpec), here and below.
double voxel_omega2(const Material& m, double voxel_size_m, double temperature_amplitude_c,
                    double rotary_inertia_scale = 1.0);
//! Squared angular frequency of the stiffest mode of the link between materials a and b, on the
//! lighter end: axial (stiffened by the Poisson coupling up to the P-wave modulus M), bending and
//! torsion, at the largest actuated size of either end. Sets the stable step. bending_factor: the
//! link's bending and torsion stiffness over the two materials' in series (a mixed link whose
//! lateral neighbours are stiffer, engine/internal/link_confinement.hpp), 1 for a plain link.
double link_omega2(const Material& a, const Material& b, double voxel_size_m,
                   double temperature_amplitude_c, double bending_factor = 1.0,
                   double rotary_inertia_scale = 1.0);
//! The same with the volumetric modulus 3 K where it is stiffer than M (nu > 0.25): bounds the
//! modes the explicit bond damping acts on (Model::build's damping cap). Capping with M instead
//! let bodies of two stiffnesses diverge (docs/physics.md, "Known limits").
double link_damping_omega2(const Material& a, const Material& b, double voxel_size_m,
                           double temperature_amplitude_c, double bending_factor = 1.0,
                           double rotary_inertia_scale = 1.0);
//! Voxelyze's recommended step 1 / (2 pi sqrt(omega2)).
double stable_step_for(double omega2);

//! The largest stable step over Voxelyze's: kImplicitStepMultiple with the implicit bond damping
//! (implicit_sweeps > 0), else 1.
double step_multiple(int implicit_sweeps);

//! The range of time steps a body of these materials can have: shortest (the stiffest pair of
//! materials linked) and longest (the softest lone material), both times dt_fraction and the
//! step multiple of the bond damping's integration (step_multiple).
struct StepRange {
    double shortest_s = 0.0;
    double longest_s = 0.0;
};
StepRange step_range(const std::vector<Material>& materials, double voxel_size_m,
                     double dt_fraction, double temperature_amplitude_c, int implicit_sweeps,
                     double rotary_inertia_scale = 1.0);

//! The number of steps run(world, total_s, ...) takes at step dt_s.
std::int64_t steps_for(double total_s, double dt_s);

//! A one-line reason when a simulation of total_s seconds at steps in `range` is out of budget
//! (more than kMaxStepsPerSimulation, estimated for `voxels` voxels) or too coarse (fewer than
//! kMinStepsPerSimulation steps, or fewer than kMinStepsPerActuationPeriod per period when
//! actuated at frequency_hz > 0); empty when it can run.
std::string step_budget_problem(const StepRange& range, double total_s, double frequency_hz,
                                bool actuated, long long voxels);

}  // namespace bhm::engine::limits
