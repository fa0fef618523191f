#pragma once
// The tracks of a simulation that every measure of an evaluation is computed from: a few points
// and sums that are linear in the voxel positions, sampled at simulation.record_fps. The fitness
// (MeasureTracker), the exploit flags (ExploitTracker) and the behaviour descriptor
// (BehaviourTracker) read a TrackSample instead of the world, so samples that were not simulated
// but extrapolated (evo/evaluate/periodic_end.hpp) give every measure exactly as a simulated one.
#include <array>
#include <cstdint>
#include <vector>

#include "evo/experiment/experiment.hpp"

namespace bhm::engine {
class World;
}

namespace bhm::evo {

using Vec3 = std::array<double, 3>;

//! The voxels (model indices) at the two ends of the bend line: the base layer (the first fixed
//! face's, x- when none is fixed) and the filled layer farthest from it. Both empty for a body of
//! a single layer along that axis.
struct BendLayers {
    std::vector<int> base, tip;
};
BendLayers bend_layers(const Experiment& experiment, const engine::World& world);

//! The two voxel groups of the detached-motion flag (evo/evaluate/exploit_flags.hpp): "base" = free
//! anchored voxels 1 or 2 hops from a held one, "moving" = every free anchored voxel; with the
//! mean squared hop count of each, the mass and thinness of every voxel.
struct ExploitGroups {
    std::vector<int> base, moving;
    double base_mean_s2 = 0.0, moving_mean_s2 = 0.0;
    std::vector<double> mass_kg;     //!< (voxels)
    std::vector<std::uint8_t> thin;  //!< (voxels) 1 for a voxel with <= 2 filled neighbours
    double total_mass_kg = 0.0;
};

//! One sample of the tracks, positions in metres (world frame).
struct TrackSample {
    double t_s = 0.0;
    Vec3 com_m{};             //!< centre of mass
    Vec3 bend_base_m{};       //!< centroid of the bend line's base layer (0 without a bend line)
    Vec3 bend_tip_m{};        //!< centroid of its far-end layer (0 without a bend line)
    Vec3 behaviour_tip_m{};   //!< the descriptor's tip: bend_tip_m, or every voxel's centroid
    Vec3 exploit_base_m{};    //!< centroid of ExploitGroups::base (0 when empty)
    Vec3 exploit_moving_m{};  //!< centroid of ExploitGroups::moving (0 when empty)
    //! sum of m_i (p_i - p_i at settle_s) over every voxel, and over the thin ones (kg m); zero
    //! before the first sample at or after settle_s.
    Vec3 mass_moment{}, thin_mass_moment{};

    static constexpr int kTracks = 8;  //!< the Vec3 members above, in order
    Vec3& track(int k);
    const Vec3& track(int k) const;
};

//! Samples the tracks of one world (stateful: it keeps the positions at settle_s).
//! A sample is due at a time between two steps (k / record_fps is rarely a whole number of
//! steps); sample(world) takes the tracks at the world's own step, sample_at(world, due) at the
//! due time itself, linear in time between the step before it (kept by before(world, due)) and
//! the step at or past it. Every track is linear in the voxel positions, so this is each voxel's
//! position interpolated, and the bend direction (tip - base) is interpolated as a vector.
//! Without it a sample's phase jitters within a step from one drive period to the next, which on
//! a small walker was most of the period-to-period residual (docs/benchmarks.md, issue 42).
class TrackSampler {
  public:
    TrackSampler(const Experiment& experiment, const engine::World& world);
    //! The tracks at the world's step (t_s = its time).
    TrackSample sample(const engine::World& world);
    //! Keeps the tracks of the world one step before a sample due at due_s.
    void before(const engine::World& world, double due_s);
    //! The tracks at due_s (t_s = due_s), the world at the first step at or past it: interpolated
    //! from the step kept by before() when that was the step before this one, else the world's.
    TrackSample sample_at(const engine::World& world, double due_s);
    const BendLayers& layers() const { return layers_; }
    const ExploitGroups& groups() const { return groups_; }

  private:
    //! Every track but the mass moments at the world's step.
    TrackSample positions_of(const engine::World& world) const;
    //! The mass moments of the world's step against reference_.
    void add_moments(const engine::World& world, TrackSample& s) const;
    double settle_s_;
    BendLayers layers_;
    std::vector<int> behaviour_tip_;
    ExploitGroups groups_;
    bool has_reference_ = false;
    std::vector<Vec3> reference_;  //!< (voxels) positions at settle_s
    //! What before() kept: the tracks one step before a due time, the step's index, and (only
    //! before the sample that becomes the reference) every voxel's position.
    TrackSample before_{};
    std::int64_t before_step_ = -1;
    std::vector<Vec3> before_positions_;
};

ExploitGroups exploit_groups(const Experiment& experiment, const engine::World& world);

//! The centroid of some voxels' positions (the zero vector for none).
Vec3 centroid_of(const engine::World& world, const std::vector<int>& voxels);

//! The time sample k of a run of total_s sampled every sample_period_s (1 / record_fps, computed
//! so) with steps of dt_s is due, as engine::run schedules it: k x sample_period_s, the last one
//! (within half a step of total_s) at total_s. TrackSampler::sample_at samples the tracks at it.
double sample_due_s(std::int64_t k, double sample_period_s, double total_s, double dt_s);

//! True once t is at or past settle_s: a due time computed as k / record_fps may land a rounding
//! below settle_s, and the tolerance keeps t = settle_s itself.
inline bool settled(double t_s, double settle_s) {
    return t_s >= settle_s - 1e-9;
}

}  // namespace bhm::evo
