#pragma once
// Private to the engine: the changing state of one World, structure of arrays over the body's
// voxel slots (see model_data.hpp for the layout; positions relative to Model::Data::origin_m).
// Double for pose and velocity (small per-step increments must not be rounded away), float for the
// per-link scratch that the link kernel writes.
#include <array>
#include <cstdint>
#include <memory>
#include <string>
#include <vector>

#include "engine/internal/model_data.hpp"
#include "engine/model.hpp"
#include "engine/world.hpp"

namespace bhm::engine {

//! Per voxel slot: 13 doubles of pose/velocity, the static-friction flag and the external
//! force: 136 bytes per voxel.
struct VoxelState {
    std::array<std::vector<double>, 3> pos;   //!< centre (m)
    std::array<std::vector<double>, 4> quat;  //!< w, x, y, z; body to world
    //! quat rounded to float, written by the voxel pass: the float link pass reads only these
    //! (half the bytes to gather, no conversions in the hottest loop; the same values).
    std::array<std::vector<float>, 4> quat_f;
    std::array<std::vector<double>, 3> vel;    //!< m/s
    std::array<std::vector<double>, 3> omega;  //!< rad/s, world frame
    std::vector<double> stuck;                 //!< 1 = held by static friction
    std::array<std::vector<double>, 3> ext_force;
    std::vector<double> refused;  //!< scratch of the voxel pass: 1 = insane new state
    //! Implicit bond damping only (damping_pass.hpp): the velocities before the damping, v*
    std::array<std::vector<double>, 3> vel_star;
    std::array<std::vector<double>, 3> omega_star;
    //! The last step's damping change v - v*, the next step's first guess (v* + it)
    std::array<std::vector<double>, 3> vel_delta;
    std::array<std::vector<double>, 3> omega_delta;
};

//! Per link slot of one axis (slot v = the link of voxel v to its + neighbour): the forces the link
//! pass writes for the voxel pass to gather (world frame; the +end receives +force, the -end
//! -force), and the link's deformation at the previous step (its backward difference is the
//! deformation rate used by bond damping).
struct LinkScratch {
    std::vector<float> storage;     //!< all arrays below, each of (kLinkLead + stored) floats
    std::array<float*, 3> force{};  //!< on the + end; the - end gets the opposite
    std::array<float*, 3> moment_neg{};
    std::array<float*, 3> moment_pos{};
    float* prev_extension = nullptr;
    //! With the Poisson coupling on, its strain pass measures every link's chord (+ end minus
    //! - end, an absent link's the straight rest chord) and length once, and the link pass reads
    //! them instead of measuring again from the double positions. Components in the axis's own
    //! order: along the link axis, then the next two axes cyclically (link_kinematics.hpp).
    std::array<float*, 3> chord{};
    float* length = nullptr;
    std::array<float*, 3> prev_theta_neg{};
    std::array<float*, 3> prev_theta_pos{};
    //! The implicit bond damping's state per link (damping_pass.hpp): beta times the extension
    //! rate and the two ends' rotation rates relative to the link frame (world axes), as the
    //! last sweep relaxed them; the loads are rebuilt from them at the current chord.
    float* damp_extension = nullptr;
    std::array<float*, 3> damp_turn_neg{};
    std::array<float*, 3> damp_turn_pos{};
};

//! Per step scratch of the Poisson pass, and its one piece of state: the lateral-strain
//! relaxation d of every isolated link (poisson.hpp), kept from step to step.
struct PoissonScratch {
    //! All per-slot arrays below: kLinkLead zero slots, then stored + kLanes.
    std::array<std::vector<float>, 3> storage;
    std::array<float*, 3> strain{};     //!< link slot: (length - rest) / L
    std::array<float*, 3> pair_d{};     //!< link slot: d the next forces use (extrapolated, state)
    std::array<float*, 3> pair_last{};  //!< link slot: relaxed d of the last step (state)
    std::array<float*, 3> grad_neg{};   //!< voxel: dW/de of its - half-link (per volume)
    std::array<float*, 3> grad_pos{};   //!< voxel: dW/de of its + half-link
    std::array<float*, 3> far_neg{};    //!< voxel: dW/de of the link before its - neighbour
    std::array<float*, 3> far_pos{};    //!< voxel: dW/de of the link after its + neighbour
    std::array<float*, 3> dgrad_neg{};  //!< voxel: dW/dd of its - link
    std::array<float*, 3> dgrad_pos{};  //!< voxel: dW/dd of its + link
    //! Filled only at the entries of PoissonParams' far lists (zero elsewhere, never written):
    std::array<float*, 3> far_strain_neg{};  //!< voxel: strain of its - side's far link
    std::array<float*, 3> far_strain_pos{};  //!< voxel: strain of its + side's far link
    std::array<float*, 3> far_from_below{};  //!< link slot: far_pos of the voxel below it
    std::array<float*, 3> far_from_above{};  //!< link slot: far_neg of the voxel two above it
};

//! Per edge spring (edge_springs.hpp): its loads, written before they are scattered to voxels.
struct EdgeScratch {
    //! The step's force (x, y, z; N) and spin increment (x, y, z), a's (end 0) at n and b's
    //! (end 1) at springs + n
    std::array<std::vector<float>, 6> increment;
    //! Per voxel slot: VoxelState::ext_force plus the springs' forces of the step, which the voxel
    //! pass takes as its applied force (so static friction weighs them with the links'); the
    //! slots of voxels in no spring hold ext_force (World::set_external_force writes both)
    std::array<std::vector<double>, 3> force;
    //! state: the gap's G0 (x, y, z) and G1 (x, y, z) of the last step, whose change the
    //! springs' damping takes (edge_springs.cpp); 0 at rest
    std::array<std::vector<float>, 6> last_gap;
};

struct World::State {
    std::shared_ptr<const Model> model;
    const Model::Data* data = nullptr;  //!< the model's data, or delayed_data
    //! A body with delayed muscle stimuli (MuscleDrive::delayed): the World's own copy of the
    //! model data, whose actuated coefficients write_delayed_drive rewrites at each step's time
    //! (mutable: the const readers, poses and energy, rewrite it at the time they report).
    std::unique_ptr<Model::Data> delayed_data;
    VoxelState voxels;
    std::array<LinkScratch, 3> links;
    PoissonScratch poisson;
    EdgeScratch edges;
    std::int64_t steps = 0;
    std::int64_t rested_steps = 0;  //!< of steps, those passed at rest (World::rest_until)
    bool diverged = false;
    std::string divergence_reason;
};

}  // namespace bhm::engine
