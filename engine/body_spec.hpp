#pragma once
// The input to the engine: one body on its lattice, its materials and the physical settings.
// Everything here is SI. The engine knows nothing of JSON, CPPNs or fitness: evo/ and app/ fill
// this.
#include <cstdint>
#include <vector>

namespace bhm::engine {

//! How an active material is driven (docs/physics.md, "Actuation"): Sine is the paper's
//! isotropic thermal expansion, cte x A sin(2 pi f t + phase), the default; Muscle is
//! contraction along a fibre axis with twitch activation dynamics (engine/muscle.hpp).
enum class ActuationModel : std::uint8_t { Sine = 0, Muscle = 1 };
//! What excites a muscle: an external pulse train (electrical or optical, with an optional on/off
//! schedule) or its own spontaneous beating (cardiomyocytes) at a fixed rate.
enum class MuscleStimulus : std::uint8_t { PulseTrain = 0, Beating = 1 };

//! A cell's entry in BodySpec::fibre_axis meaning "its material's Muscle::fibre_axis".
inline constexpr std::uint8_t kMaterialFibreAxis = 255;

//! The muscle model of one material (used when Material::actuation_model is Muscle).
struct Muscle {
    int fibre_axis = 0;               //!< 0 = x, 1 = y, 2 = z (lattice axes)
    double contraction_strain = 0.0;  //!< free shortening along the fibre at full activation; > 0
    double rise_s = 0.03;             //!< activation time constant while stimulated
    double decay_s = 0.06;            //!< deactivation time constant between stimuli
    MuscleStimulus stimulus = MuscleStimulus::PulseTrain;
    double frequency_hz = 1.0;     //!< pulses (or beats) per second
    double pulse_width_s = 0.01;   //!< how long each pulse excites the muscle
    double train_on_s = 0.0;       //!< pulse train: length of a burst; 0 = one endless train
    double train_off_s = 0.0;      //!< pulse train: rest between bursts
    //! Fatigue (engine/muscle.hpp): time constant of the force's loss while stimulated; 0 = none
    //! (the default: the fields below are then ignored).
    double fatigue_s = 0.0;
    double recovery_s = 0.0;      //!< fatigue: time constant of the recovery at rest
    double fatigue_floor = 0.0;   //!< fatigue: the fraction of the force a long stimulus keeps
    bool operator==(const Muscle&) const = default;
};

//! One material of the palette (paper Table 1). Material index k in a lattice means materials[k-1].
struct Material {
    double youngs_modulus_pa = 5e6;  //!< E
    double density_kg_m3 = 1000.0;   //!< rho
    double poisson_ratio = 0.35;     //!< nu, in (-1, 0.5)
    double cte_per_c = 0.0;          //!< linear thermal expansion; > 0 makes the voxel active
    double static_friction = 1.0;    //!< mu_s against the floor
    double dynamic_friction = 0.5;   //!< mu_k against the floor
    ActuationModel actuation_model = ActuationModel::Sine;
    Muscle muscle;  //!< used when actuation_model is Muscle (then cte_per_c must be 0)
    bool operator==(const Material&) const = default;
};

//! Whether a material's voxels are driven: cte > 0 under the sine model, a contraction strain
//! > 0 under the muscle model.
inline bool is_active(const Material& m) {
    return m.actuation_model == ActuationModel::Muscle ? m.muscle.contraction_strain > 0.0
                                                       : m.cte_per_c > 0.0;
}

struct Environment {
    double gravity_m_s2 = -9.81;  //!< along z; negative pulls toward the floor
    bool floor = true;            //!< penalty contact with the plane z = 0
    bool operator==(const Environment&) const = default;
};

struct Damping {
    double bond_ratio =
        1.0;  //!< fraction of critical damping of each link (Voxelyze zeta_internal)
    double global_ratio = 0.01;    //!< damping of each voxel toward rest (zeta_global)
    double collision_ratio = 0.8;  //!< damping of floor contact (zeta_collision)
    //! How the bond damping is integrated: n > 0 = implicit, n sweeps toward (M + dt C) v = M v*
    //! (v* the velocity after the elastic forces), beta in full and a stable step 2.2x as long
    //! (default: one sweep); 0 = explicit (velocity-lagged, beta capped so that it stays stable
    //! at the step), as before issue 23 (docs/physics.md, "Damping and the step").
    int implicit_sweeps = 1;
    bool operator==(const Damping&) const = default;
};

struct Actuation {
    double frequency_hz = 2.0;               //!< f in dT = A sin(2 pi f t + phase)
    double temperature_amplitude_c = 14.47;  //!< A
    double start_s = 1.0;                    //!< actuation is off before this time (settling)
    bool operator==(const Actuation&) const = default;
};

//! Lattice cell index: x + nx * (y + ny * z), x fastest (VoxCAD's convention).
struct BodySpec {
    int nx = 0, ny = 0, nz = 0;
    double voxel_size_m = 0.01;
    std::vector<std::uint8_t> material;  //!< (nx*ny*nz) 0 = empty, k = materials[k-1]
    //! (nx*ny*nz) or empty; 1 = held: the centre fixed, the rotation too, except in a held face
    //! or line, where it turns against a spring to the clamp (engine/model.cpp)
    std::vector<std::uint8_t> fixed;
    std::vector<float> phase_rad;  //!< (nx*ny*nz) or empty; actuation phase per cell
    //! (nx*ny*nz) or empty (= 1 everywhere); a cell's drive amplitude in [0, 1] (issue 44: an
    //! evolved controller): multiplies cte A of the sine model and the contraction strain of the
    //! muscle model. At most 1, so the stable step found for the full drive still holds.
    std::vector<float> amplitude_scale;
    //! (nx*ny*nz) or empty; a muscle cell's own fibre axis, 0 = x, 1 = y, 2 = z, or
    //! kMaterialFibreAxis for its material's (issue 43: fibres per voxel, e.g. from a CPPN).
    //! Ignored in cells that are not muscle; empty = every cell takes its material's axis.
    std::vector<std::uint8_t> fibre_axis;
    std::vector<Material> materials;
    Environment environment;
    Damping damping;
    Actuation actuation;
    double dt_fraction = 0.9;  //!< fraction of the largest stable step
    //! Each voxel's rotational inertia over a solid cube's, m L^2 / 6 (rotary inertia scaling, as
    //! explicit FEM codes scale beams' and shells' rotary inertia so that their rotational modes
    //! do not bound the step): the rotational modes slow by 1 / sqrt(s), the stable step follows.
    //! 1 = the cube's, the default (issue 42, docs/benchmarks.md "the step size itself").
    double rotary_inertia_scale = 1.0;

    int cell_count() const { return nx * ny * nz; }
    int cell_index(int x, int y, int z) const { return x + nx * (y + ny * z); }
};

}  // namespace bhm::engine
