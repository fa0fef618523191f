// World: one simulation of one Model. A step = three link passes (x, y, z) + one voxel pass.
#include "engine/world.hpp"

#include <algorithm>
#include <cmath>
#include <numbers>
#include <sstream>
#include <stdexcept>
#include <string>

#include "engine/internal/damping_pass.hpp"
#include "engine/internal/edge_springs.hpp"
#include "engine/internal/link_pass.hpp"
#include "engine/internal/muscle_drive.hpp"
#include "engine/internal/poisson.hpp"
#include "engine/internal/voxel_pass.hpp"
#include "engine/internal/world_state.hpp"
#include "engine/limits.hpp"

namespace bhm::engine {
namespace {

void init_voxels(const Model::Data& d, VoxelState& s) {
    const int n = d.stored;
    for (int i = 0; i < 3; ++i) {
        s.pos[i].assign(n, 0.0);
        s.vel[i].assign(n, 0.0);
        s.omega[i].assign(n, 0.0);
        s.ext_force[i].assign(n, 0.0);
    }
    for (int i = 0; i < 4; ++i) {
        s.quat[i].assign(n, i == 0 ? 1.0 : 0.0);
        s.quat_f[i].assign(n, i == 0 ? 1.0f : 0.0f);
    }
    if (d.implicit_sweeps > 0)
        for (int i = 0; i < 3; ++i) {
            s.vel_star[i].assign(n, 0.0);
            s.omega_star[i].assign(n, 0.0);
            s.vel_delta[i].assign(n, 0.0);
            s.omega_delta[i].assign(n, 0.0);
        }
    s.stuck.assign(n, 0.0);
    s.refused.assign(n, 0.0);
    // Every slot, dummies included, sits on its rest point (relative to the body's origin).
    for (int v = 0; v < n; ++v)
        for (int i = 0; i < 3; ++i)
            s.pos[i][v] = d.rest_position[v][i];
}

void init_links(const Model::Data& d, LinkScratch& l) {
    // 30 arrays; the voxel pass reads slots before 0 (kNoLink, x of voxel 0, uniform runs), so
    // each has link_lead zero slots first.
    const std::size_t span = static_cast<std::size_t>(d.link_lead) + d.stored;
    l.storage.assign(30 * span, 0.0f);
    float* base = l.storage.data() + d.link_lead;
    auto next = [&]() {
        float* p = base;
        base += span;
        return p;
    };
    for (int i = 0; i < 3; ++i)
        l.force[i] = next();
    for (int i = 0; i < 3; ++i)
        l.moment_neg[i] = next();
    for (int i = 0; i < 3; ++i)
        l.moment_pos[i] = next();
    l.prev_extension = next();
    for (int i = 0; i < 3; ++i)
        l.prev_theta_neg[i] = next();
    for (int i = 0; i < 3; ++i)
        l.prev_theta_pos[i] = next();
    for (int i = 0; i < 3; ++i)
        l.chord[i] = next();
    l.length = next();
    l.damp_extension = next();
    for (int i = 0; i < 3; ++i)
        l.damp_turn_neg[i] = next();
    for (int i = 0; i < 3; ++i)
        l.damp_turn_pos[i] = next();
}

// The two actuation signals every pass reads (sin_t, cos_t: the sine model's sin and cos of
// 2 pi f tau, or a muscle body's two activations, muscle_drive.hpp) and their rates.
struct Phase {
    double sin_t = 0.0, cos_t = 0.0;
    double rate_sin = 0.0, rate_cos = 0.0;  //!< d/dt of sin_t and cos_t
};

Phase actuation_phase(const Model::Data& d, double t) {
    // A delayed muscle body's coefficients already hold each voxel's activation at t
    // (refresh_delayed_drive): rest = base + 1 x rest_sin, its rate 1 x rest_cos.
    if (d.muscle.delayed) return {1.0, 0.0, 0.0, 1.0};
    if (d.muscle.signals > 0) {
        const DriveSignals s = muscle_signals(d.muscle, t);
        return {s.c0, s.c1, s.rate0, s.rate1};
    }
    const Actuation& a = d.spec.actuation;
    const double tau = t - a.start_s;
    if (!d.any_active || tau < 0.0) return {};
    const double angle = 2.0 * std::numbers::pi * a.frequency_hz * tau;
    const double omega = 2.0 * std::numbers::pi * a.frequency_hz;
    const double sin_t = std::sin(angle), cos_t = std::cos(angle);
    return {sin_t, cos_t, omega * cos_t, -omega * sin_t};
}

// A delayed muscle body: its World's copy of the model data at time t (muscle_drive.hpp).
void refresh_delayed_drive(World::State& s, double t) {
    if (s.delayed_data) write_delayed_drive(s.model->data(), *s.delayed_data, t);
}

const char* kAxisNames[3] = {"x", "y", "z"};

}  // namespace

World::World(std::shared_ptr<const Model> model) : state_(std::make_unique<State>()) {
    if (!model) throw std::invalid_argument("World: null model");
    state_->model = std::move(model);
    state_->data = &state_->model->data();
    if (state_->data->muscle.delayed) {
        state_->delayed_data = std::make_unique<Model::Data>(*state_->data);
        state_->data = state_->delayed_data.get();
        refresh_delayed_drive(*state_, 0.0);
    }
    const Model::Data& d = *state_->data;
    init_voxels(d, state_->voxels);
    if (d.poisson.active) prepare_poisson_scratch(d, state_->poisson);
    for (auto& increment : state_->edges.increment)
        increment.assign(2 * static_cast<std::size_t>(d.edge_springs.size()), 0.0f);
    if (d.edge_springs.size() > 0) state_->edges.force = state_->voxels.ext_force;
    for (auto& gap : state_->edges.last_gap)
        gap.assign(d.edge_springs.size(), 0.0f);
    // At t = 0 every link is straight at its lattice length; its extension is that length minus
    // its (possibly already actuated) rest length, so the first damping rate is zero.
    const Phase phase = actuation_phase(d, 0.0);
    for (int axis = 0; axis < 3; ++axis) {
        LinkScratch& l = state_->links[axis];
        init_links(d, l);
        const LinkParams& p = d.links[axis];
        for (int c = 0; c < d.stored; ++c) {
            const float rest = p.rest_base[c] + static_cast<float>(phase.sin_t) * p.rest_sin[c] +
                               static_cast<float>(phase.cos_t) * p.rest_cos[c];
            l.prev_extension[c] = static_cast<float>(d.voxel_size_m) - rest;
        }
    }
}

World::~World() = default;
World::World(World&&) noexcept = default;
World& World::operator=(World&&) noexcept = default;

const Model& World::model() const {
    return *state_->model;
}

void World::step() {
    State& s = *state_;
    if (s.diverged) return;
    const Model::Data& d = *s.data;
    const double t = time_s();
    refresh_delayed_drive(s, t);
    const Phase phase = actuation_phase(d, t);
    const float sin_t = static_cast<float>(phase.sin_t), cos_t = static_cast<float>(phase.cos_t);

    if (d.poisson.active) poisson_pass(d, s.voxels, s.links, s.poisson, sin_t, cos_t);
    int bad_links = 0;
    for (int axis = 0; axis < 3; ++axis)
        bad_links += link_pass(d, s.voxels, s.links[axis], d.poisson.active ? &s.poisson : nullptr,
                               axis, sin_t, cos_t);
    if (bad_links != 0) {
        std::ostringstream why;
        why << "link stretched by more than a voxel, squeezed below a tenth of one, or sheared "
               "past 120 degrees";
        for (int axis = 0; axis < 3; ++axis) {
            const int c = first_bad_link(d, s.voxels, s.links[axis], axis, sin_t, cos_t);
            if (c < 0) continue;
            const int b = axis == 0 ? c + 1 : d.plus[axis][c];
            why << " (" << kAxisNames[axis] << " link from voxel " << c << " to voxel " << b << ": "
                << describe_link(d, s.voxels, axis, c, sin_t, cos_t) << ")";
            break;
        }
        why << " at t = " << t << " s, step " << s.steps;
        s.diverged = true;
        s.divergence_reason = why.str();
        return;
    }

    const bool springs = d.edge_springs.size() > 0;
    if (springs) edge_pass(d, s.voxels, s.edges, phase.sin_t, phase.cos_t);
    VoxelPassInput in;
    if (springs) in.applied_force = &s.edges.force;
    in.sin_t = phase.sin_t;
    in.cos_t = phase.cos_t;
    in.gravity_m_s2 = d.spec.environment.gravity_m_s2;
    // The floor is z = 0 in the world, -origin_z in the body's frame (model_data.hpp).
    in.floor_z = d.spec.environment.floor ? -d.origin_m[2] : -1e300;
    int bad_voxels = 0;
    if (d.implicit_sweeps > 0) {
        // Elastic and other forces give v*; the bond damping solves (M + dt C) v = M v* by
        // Jacobi sweeps, the last of which moves the pose (damping_pass.hpp).
        in.velocity_only = true;
        voxel_pass(d, s.voxels, s.links, in);
        const auto rate_sin = static_cast<float>(phase.rate_sin);
        const auto rate_cos = static_cast<float>(phase.rate_cos);
        const PoissonScratch* poisson = d.poisson.active ? &s.poisson : nullptr;
        for (int sweep = 1; sweep <= d.implicit_sweeps; ++sweep) {
            for (int axis = 0; axis < 3; ++axis)
                damping_link_pass(d, s.voxels, s.links[axis], poisson, axis, sin_t, cos_t, rate_sin,
                                  rate_cos);
            bad_voxels = damping_voxel_pass(d, s.voxels, s.links, sweep == d.implicit_sweeps);
        }
    } else {
        bad_voxels = voxel_pass(d, s.voxels, s.links, in);
    }
    if (bad_voxels != 0) {
        std::ostringstream why;
        why << "voxel state non-finite or moving more than one voxel (or one radian) per step";
        const int v = first_refused_voxel(d, s.voxels);
        if (v >= 0) why << " (voxel " << v << ")";
        why << " at t = " << t << " s, step " << s.steps;
        s.diverged = true;
        s.divergence_reason = why.str();
        return;
    }
    ++s.steps;
}

bool World::advance_to(double target_s) {
    State& s = *state_;
    const double dt = s.data->dt_s;
    while (!s.diverged && static_cast<double>(s.steps) * dt < target_s)
        step();
    return !s.diverged;
}

std::int64_t first_step_at_or_past(double time_s, double dt_s) {
    auto n = static_cast<std::int64_t>(std::ceil(time_s / dt_s));
    while (n > 0 && static_cast<double>(n - 1) * dt_s >= time_s)
        --n;
    while (static_cast<double>(n) * dt_s < time_s)
        ++n;
    return n;
}

void World::rest_until(double target_s) {
    State& s = *state_;
    const double dt = s.data->dt_s;
    if (s.diverged) return;
    // The same first step at or past target_s as advance_to reaches.
    const std::int64_t n = first_step_at_or_past(target_s, dt);
    if (n <= s.steps) return;
    s.rested_steps += n - s.steps;
    s.steps = n;
}

double World::time_s() const {
    return static_cast<double>(state_->steps) * state_->data->dt_s;
}
std::int64_t World::steps() const {
    return state_->steps;
}
std::int64_t World::integrated_steps() const {
    return state_->steps - state_->rested_steps;
}
bool World::diverged() const {
    return state_->diverged;
}
const std::string& World::divergence_reason() const {
    return state_->divergence_reason;
}

std::array<double, 3> World::centre_of_mass_m() const {
    const Model::Data& d = *state_->data;
    const VoxelState& s = state_->voxels;
    std::array<double, 3> sum{0.0, 0.0, 0.0};
    for (int v = 0; v < d.voxels; ++v)
        for (int i = 0; i < 3; ++i)
            sum[i] += d.mass[v] * s.pos[i][v];
    for (int i = 0; i < 3; ++i)
        sum[i] = sum[i] / d.total_mass_kg + d.origin_m[i];
    return sum;
}

std::array<double, 3> World::voxel_position_m(int v) const {
    const Model::Data& d = *state_->data;
    if (v < 0 || v >= d.voxels) throw std::out_of_range("World::voxel_position_m: no such voxel");
    const VoxelState& s = state_->voxels;
    return {s.pos[0][v] + d.origin_m[0], s.pos[1][v] + d.origin_m[1], s.pos[2][v] + d.origin_m[2]};
}

void World::read_poses(VoxelPoses& out) const {
    const Model::Data& d = *state_->data;
    const VoxelState& s = state_->voxels;
    const int n = d.voxels;
    out.time_s = time_s();
    out.position_m.resize(3 * static_cast<std::size_t>(n));
    out.orientation.resize(4 * static_cast<std::size_t>(n));
    out.size_m.resize(3 * static_cast<std::size_t>(n));
    const Phase phase = actuation_phase(d, out.time_s);
    const DelayedActivations delayed =
        d.muscle.delayed ? delayed_activations(d.muscle, out.time_s) : DelayedActivations{};
    for (int v = 0; v < n; ++v) {
        for (int i = 0; i < 3; ++i)
            out.position_m[3 * v + i] = static_cast<float>(s.pos[i][v] + d.origin_m[i]);
        for (int i = 0; i < 4; ++i)
            out.orientation[4 * v + i] = static_cast<float>(s.quat[i][v]);
        const double size =
            d.voxel_size_m * (1.0 + d.act_sin[v] * phase.sin_t + d.act_cos[v] * phase.cos_t);
        for (int i = 0; i < 3; ++i)
            out.size_m[3 * v + i] = static_cast<float>(size);
        if (d.muscle.signals == 0) continue;
        // A muscle voxel is shorter along its fibre than across it (muscle_drive.hpp).
        for (int i = 0; i < 3; ++i)
            out.size_m[3 * v + i] = static_cast<float>(
                d.voxel_size_m * (d.muscle.delayed
                                      ? delayed_axis_scale(d, v, i, delayed)
                                      : muscle_axis_scale(d, v, i, phase.sin_t, phase.cos_t)));
    }
}

void World::set_external_force(int v, std::array<double, 3> force_n) {
    if (v < 0 || v >= state_->data->voxels)
        throw std::out_of_range("World::set_external_force: no such voxel");
    for (int i = 0; i < 3; ++i) {
        state_->voxels.ext_force[i][v] = force_n[i];
        // The voxel pass reads the springs' sum, which holds the external force too.
        if (!state_->edges.force[i].empty()) state_->edges.force[i][v] = force_n[i];
    }
}

double World::kinetic_energy_j() const {
    const Model::Data& d = *state_->data;
    const VoxelState& s = state_->voxels;
    const double L = d.voxel_size_m;
    double e = 0.0;
    for (int c = 0; c < d.voxels; ++c) {
        const double m = d.mass[c], inertia = d.rotary_inertia_scale * m * L * L / 6.0;
        for (int i = 0; i < 3; ++i)
            e += 0.5 * (m * s.vel[i][c] * s.vel[i][c] + inertia * s.omega[i][c] * s.omega[i][c]);
    }
    return e;
}

std::array<double, 3> World::linear_momentum() const {
    const Model::Data& d = *state_->data;
    const VoxelState& s = state_->voxels;
    std::array<double, 3> p{0.0, 0.0, 0.0};
    for (int c = 0; c < d.voxels; ++c)
        for (int i = 0; i < 3; ++i)
            p[i] += d.mass[c] * s.vel[i][c];
    return p;
}

std::array<double, 3> World::angular_momentum() const {
    const Model::Data& d = *state_->data;
    const VoxelState& s = state_->voxels;
    const double L = d.voxel_size_m;
    std::array<double, 3> h{0.0, 0.0, 0.0};
    for (int c = 0; c < d.voxels; ++c) {
        const double m = d.mass[c], inertia = d.rotary_inertia_scale * m * L * L / 6.0;
        const double r[3] = {s.pos[0][c] + d.origin_m[0], s.pos[1][c] + d.origin_m[1],
                             s.pos[2][c] + d.origin_m[2]};
        const double v[3] = {s.vel[0][c], s.vel[1][c], s.vel[2][c]};
        h[0] += m * (r[1] * v[2] - r[2] * v[1]) + inertia * s.omega[0][c];
        h[1] += m * (r[2] * v[0] - r[0] * v[2]) + inertia * s.omega[1][c];
        h[2] += m * (r[0] * v[1] - r[1] * v[0]) + inertia * s.omega[2][c];
    }
    return h;
}

double World::potential_energy_j() const {
    refresh_delayed_drive(*state_, time_s());
    const Model::Data& d = *state_->data;
    const VoxelState& s = state_->voxels;
    const Phase phase = actuation_phase(d, time_s());
    double e = 0.0;
    for (int axis = 0; axis < 3; ++axis)
        e += link_elastic_energy(d, s, axis, static_cast<float>(phase.sin_t),
                                 static_cast<float>(phase.cos_t));
    e += poisson_cross_energy(d, s, state_->poisson, static_cast<float>(phase.sin_t),
                              static_cast<float>(phase.cos_t));
    const double g = d.spec.environment.gravity_m_s2;
    for (int c = 0; c < d.voxels; ++c) {
        const double z = s.pos[2][c] + d.origin_m[2];
        e -= d.mass[c] * g * z;
        e += 4.0 * d.wall_stiffness[c] * (1.0 - std::fabs(s.quat[0][c]));  // voxel_pass.cpp
        if (!d.spec.environment.floor) continue;
        const double half =
            0.5 * d.voxel_size_m * (1.0 + d.act_sin[c] * phase.sin_t + d.act_cos[c] * phase.cos_t);
        const double penetration = half - z;
        if (penetration > 0.0) e += 0.5 * d.floor_k[c] * penetration * penetration;
    }
    return e;
}

std::array<double, 4> World::voxel_orientation(int v) const {
    if (v < 0 || v >= state_->data->voxels)
        throw std::out_of_range("World::voxel_orientation: no such voxel");
    const VoxelState& s = state_->voxels;
    return {s.quat[0][v], s.quat[1][v], s.quat[2][v], s.quat[3][v]};
}

void run(World& world, double total_s, double sample_hz, const RunHooks& hooks) {
    if (!(sample_hz > 0.0) || !std::isfinite(sample_hz))
        throw std::invalid_argument("run: sample_hz must be positive");
    if (hooks.poll && hooks.poll_steps < 1)
        throw std::invalid_argument("run: poll_steps must be at least 1");
    const double period = 1.0 / sample_hz;
    const double dt = world.model().dt_s();
    const double half_step = 0.5 * dt;
    // Sample k is due at k / sample_hz; the last one at total_s. A world handed over part way
    // (time_s() > 0) is observed once now, then from the next due sample on.
    if (world.diverged()) return;
    // A simulation never silently runs zero steps: a step longer than twice the whole duration
    // is a spec out of the envelope (limits::step_budget_problem refuses it up front).
    if (world.steps() == 0 && total_s > 0.0 && limits::steps_for(total_s, dt) == 0)
        throw std::invalid_argument("run: a step of " + std::to_string(dt) +
                                    " s is longer than twice the " + std::to_string(total_s) +
                                    " s to simulate: zero steps would run");
    auto poll = [&] { return hooks.poll && hooks.poll(world) == RunVerdict::Stop; };
    // Steps to the first step at or past target, polling every poll_steps steps; false when the
    // world diverged or a poll said Stop.
    auto advance = [&](double target) {
        if (!hooks.poll) return world.advance_to(target);
        while (world.time_s() < target) {
            const double slice_end = static_cast<double>(world.steps() + hooks.poll_steps) * dt;
            if (!world.advance_to(std::min(target, slice_end))) return false;
            if (world.time_s() < target && poll()) return false;
        }
        return true;
    };
    if (hooks.observe) hooks.observe(world);
    if (poll()) return;
    if (world.time_s() >= total_s - half_step) return;
    for (auto k = static_cast<std::int64_t>(std::floor(world.time_s() / period)) + 1;; ++k) {
        double due = static_cast<double>(k) * period;
        const bool last = due >= total_s - half_step;
        if (last) due = total_s;
        if (hooks.before_sample) {
            // The step before the due time, then the one that reaches or passes it.
            const std::int64_t n = first_step_at_or_past(due, dt);
            if (world.steps() < n) {
                if (!advance(static_cast<double>(n - 1) * dt)) return;
                hooks.before_sample(world, due);
            }
        }
        if (!advance(due)) return;  // diverged (the caller reads the reason) or stopped
        if (hooks.observe) hooks.observe(world);
        if (poll() || last) return;
    }
}

void run(World& world, double total_s, double sample_hz,
         const std::function<void(const World&)>& observe) {
    RunHooks hooks;
    hooks.observe = observe;
    run(world, total_s, sample_hz, hooks);
}

}  // namespace bhm::engine
