#pragma once
// The changing state of one simulation of one Model. Stepped by one thread; step() never allocates.
// CONTRACT used by evo/ and render/: keep these public members; the engine may add more.
#include <array>
#include <cstdint>
#include <functional>
#include <memory>
#include <string>

#include "engine/model.hpp"
#include "engine/poses.hpp"

namespace bhm::engine {

class World {
public:
    explicit World(std::shared_ptr<const Model> model);
    ~World();
    World(World&&) noexcept;
    World& operator=(World&&) noexcept;

    const Model& model() const;

    void step();                        //!< advance by one dt (no-op once diverged)
    bool advance_to(double time_s);     //!< step until time_s() >= time_s; false if diverged

    //! Lets time pass to the first step at or past time_s without integrating: for a body at
    //! rest before anything drives it (an evaluation whose settling ended early,
    //! evo/evaluate/settle_rest.hpp). The state is kept as it is; steps() counts the steps
    //! passed, integrated_steps() only those computed. No-op once diverged or past time_s.
    void rest_until(double time_s);

    double time_s() const;
    std::int64_t steps() const;             //!< time_s() / dt
    std::int64_t integrated_steps() const;  //!< steps() less those passed at rest
    bool diverged() const;
    const std::string& divergence_reason() const;

    std::array<double, 3> centre_of_mass_m() const;
    std::array<double, 3> voxel_position_m(int v) const;
    void read_poses(VoxelPoses& out) const;  //!< resizes out once, then reuses its storage

    //! A constant external force on a voxel (tests, probes). Zero by default.
    void set_external_force(int v, std::array<double, 3> force_n);

    double kinetic_energy_j() const;
    std::array<double, 3> linear_momentum() const;

    // Additions (engine): diagnostics used by tests and probes.
    //! Elastic energy of the links + gravitational (relative to z = 0) + floor penalty springs (J).
    double potential_energy_j() const;
    //! Total angular momentum about the world origin (kg m^2/s).
    std::array<double, 3> angular_momentum() const;
    //! Orientation of voxel v as a unit quaternion w, x, y, z (body to world).
    std::array<double, 4> voxel_orientation(int v) const;

    struct State;

private:
    friend class LinearisedBody;  //!< reads the state to linearise it (engine/linearised_body.hpp)
    std::unique_ptr<State> state_;
};

//! What a run's poll hook tells it: go on, or end here (the world keeps the state reached).
enum class RunVerdict { Continue, Stop };

//! The callbacks of run(); each may be empty.
struct RunHooks {
    //! At t = 0, every 1/sample_hz seconds of simulated time and at the end.
    std::function<void(const World&)> observe;
    //! At the last step before each sample's due time (t < due), just before the step that
    //! reaches or passes it, with that due time: a caller that interpolates its samples to the
    //! due time keeps what it reads here (evo/evaluate/tracks.hpp). Not called for a sample
    //! whose step was reached before this run began (t = 0, a world handed over part way).
    std::function<void(const World&, double due_s)> before_sample;
    //! Every poll_steps steps and right after each observe: a caller pauses here (by waiting),
    //! cancels (by throwing) or ends the run early (Stop). It never changes the steps taken.
    std::function<RunVerdict(const World&)> poll;
    int poll_steps = 64;  //!< a few milliseconds even for large bodies
};

//! The index of the first step at or past time_s (what advance_to and rest_until reach).
std::int64_t first_step_at_or_past(double time_s, double dt_s);

//! Runs a world from t = 0 to total_s, calling hooks.observe(world) at t = 0 and every
//! 1/sample_hz seconds of simulated time (and at the end), at the first step at or past each due
//! time (hooks.before_sample one step earlier). Stops early on divergence or when
//! hooks.poll says Stop. Polling slices the advance without changing it: dt is fixed and
//! advance_to stops at the first step at or past its target, so the same steps are taken.
void run(World& world, double total_s, double sample_hz, const RunHooks& hooks);
void run(World& world, double total_s, double sample_hz,
         const std::function<void(const World&)>& observe);

}  // namespace bhm::engine
