#pragma once
// What `bhm simulate` measures and writes: centre of mass and tip per sample, displacements after
// settling (paper: fitness = displacement of the centre of mass, 3-D or on the YZ plane, in voxel
// lengths), and the summary / trajectory / replay files built from them. Reusable by any caller
// that steps a World (studio, tests), independent of the command line.
#include <array>
#include <cstdint>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "engine/model.hpp"
#include "engine/replay.hpp"
#include "engine/world.hpp"

namespace bhm::app {

using Vec3 = std::array<double, 3>;

//! The voxels of the highest-x lattice layer the body occupies: the free end of a body held at x-.
std::vector<int> tip_layer_voxels(const engine::Model& model);

//! Mean position of the given voxels (m). Empty list -> NaNs.
Vec3 centroid_m(const engine::World& world, const std::vector<int>& voxels);

struct TrajectorySample {
    double t_s = 0.0;
    Vec3 com_m{};  //!< mass-weighted centre of mass
    Vec3 tip_m{};  //!< centroid of the tip layer
};

//! Measures one sample of a world: its centre of mass and tip centroid at the current time.
TrajectorySample measure_sample(const engine::World& world, const std::vector<int>& tip_voxels);

//! Displacements of the centre of mass from the end of settling (t = settle_s) on.
struct DisplacementSummary {
    bool settled = false;  //!< false when the run ended before settle_s (all zero then)
    double com_start_t_s =
        0.0;  //!< time of the sample used as the start: first one at or after settle_s
    Vec3 com_start_m{};
    Vec3 com_end_m{};
    Vec3 tip_position_m{};                    //!< tip centroid of the last sample
    double displacement_3d_voxels = 0.0;      //!< |com_end - com_start| / L
    double displacement_yz_voxels = 0.0;      //!< the same projected on the YZ plane
    double max_displacement_3d_voxels = 0.0;  //!< max over samples from com_start on
    double max_displacement_yz_voxels = 0.0;
};

//! Summarizes samples in time order. A sample counts as "after settling" when t >= settle_s
//! minus a nanosecond (sample times come from summed time steps). Empty samples -> all zero.
DisplacementSummary summarize_displacements(const std::vector<TrajectorySample>& samples,
                                            double settle_s, double voxel_size_m);

//! trajectory.csv: header t_s,com_x_m,com_y_m,com_z_m,tip_x_m,tip_y_m,tip_z_m, one row per sample,
//! values with enough digits to round-trip a double.
std::string trajectory_csv(const std::vector<TrajectorySample>& samples);

//! Header of a replay of this model (lattice, voxel table); frames left empty.
engine::Replay replay_header(const engine::Model& model, double settle_s);

//! Collects samples and replay frames while engine::run calls it. Ignores a second call at the
//! same step count, so a run that observes its last sample twice does not repeat a row.
class SimulationRecorder {
  public:
    SimulationRecorder(const engine::Model& model, double settle_s, bool record_replay = true);
    void observe(const engine::World& world);

    const std::vector<TrajectorySample>& samples() const { return samples_; }
    const engine::Replay& replay() const { return replay_; }
    double settle_s() const { return settle_s_; }

  private:
    std::vector<int> tip_voxels_;
    double settle_s_;
    bool record_replay_;
    std::int64_t last_step_ = -1;
    std::vector<TrajectorySample> samples_;
    engine::Replay replay_;
};

//! Timing and health of one run, for summary.json.
struct RunStats {
    int voxels = 0;
    int links = 0;
    std::int64_t steps = 0;
    double dt_s = 0.0;
    double sim_time_s = 0.0;
    double wall_s = 0.0;
    bool diverged = false;
    std::string divergence_reason;
    double voxel_steps_per_s() const {
        return wall_s > 0.0 ? static_cast<double>(voxels) * static_cast<double>(steps) / wall_s
                            : 0.0;
    }
};

//! The figures of a finished (or diverged) simulation of `model` in `world`.
RunStats run_stats_of(const engine::Model& model, const engine::World& world, double wall_s);

//! summary.json's fields (docs in `bhm simulate --help`): run stats, then displacements.
nlohmann::ordered_json summary_json(const RunStats& stats,
                                    const DisplacementSummary& displacements);

}  // namespace bhm::app
