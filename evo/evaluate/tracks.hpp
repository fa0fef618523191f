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
class TrackSampler {
  public:
    TrackSampler(const Experiment& experiment, const engine::World& world);
    TrackSample sample(const engine::World& world);
    const BendLayers& layers() const { return layers_; }
    const ExploitGroups& groups() const { return groups_; }

  private:
    double settle_s_;
    BendLayers layers_;
    std::vector<int> behaviour_tip_;
    ExploitGroups groups_;
    bool has_reference_ = false;
    std::vector<Vec3> reference_;  //!< (voxels) positions at settle_s
};

ExploitGroups exploit_groups(const Experiment& experiment, const engine::World& world);

//! The centroid of some voxels' positions (the zero vector for none).
Vec3 centroid_of(const engine::World& world, const std::vector<int>& voxels);

//! The time at which engine::run takes sample k of a run of total_s sampled every sample_period_s
//! (1 / record_fps, computed so) with steps of dt_s: due at k x sample_period_s (the last one at
//! total_s), taken at the first step at or past it (World::advance_to).
double sample_time_s(std::int64_t k, double sample_period_s, double total_s, double dt_s);

//! True once t is at or past settle_s: samples land on or just after their nominal time, and the
//! tolerance keeps t = settle_s itself.
inline bool settled(double t_s, double settle_s) {
    return t_s >= settle_s - 1e-9;
}

}  // namespace bhm::evo
