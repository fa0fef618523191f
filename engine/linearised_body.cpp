#include "engine/linearised_body.hpp"

#include <Eigen/SparseCholesky>
#include <Eigen/SparseCore>
#include <algorithm>
#include <array>
#include <cmath>
#include <map>
#include <vector>

#include "engine/internal/edge_springs.hpp"
#include "engine/internal/link_pass.hpp"
#include "engine/internal/poisson.hpp"
#include "engine/internal/voxel_pass.hpp"
#include "engine/internal/world_state.hpp"

namespace bhm::engine {

namespace {

using Sparse = Eigen::SparseMatrix<double>;

// The engine's forces at a pose: a scratch World of the same model whose passes run at zero
// velocity, the floor switched off (its spring is added apart: linearised_body.hpp).
class ForceProbe {
  public:
    //! probe: the scratch World's state (a World of the base's model, never stepped).
    ForceProbe(World::State& probe, const World::State& base, int max_relaxations)
        : probe_(probe), base_(base), max_relaxations_(max_relaxations) {}

    World::State& state() { return probe_; }

    //! Sets the probe's pose and internal state to the base world's.
    void reset() {
        World::State& s = probe_;
        const VoxelState& b = base_.voxels;
        s.voxels.pos = b.pos;
        s.voxels.quat = b.quat;
        s.voxels.quat_f = b.quat_f;
        s.voxels.ext_force = b.ext_force;
        for (int a = 0; a < 3; ++a)
            std::copy(base_.poisson.storage[static_cast<std::size_t>(a)].begin(),
                      base_.poisson.storage[static_cast<std::size_t>(a)].end(),
                      s.poisson.storage[static_cast<std::size_t>(a)].begin());
        std::copy(base_.links[0].storage.begin(), base_.links[0].storage.end(),
                  s.links[0].storage.begin());
        std::copy(base_.links[1].storage.begin(), base_.links[1].storage.end(),
                  s.links[1].storage.begin());
        std::copy(base_.links[2].storage.begin(), base_.links[2].storage.end(),
                  s.links[2].storage.begin());
    }

    //! The generalised forces (N; N m) on every voxel slot at the probe's pose, 6 per voxel, into
    //! out; returns the Poisson passes run (the relaxed splits d converged at this pose).
    int forces(std::vector<std::array<double, 6>>& out) {
        World::State& s = probe_;
        const Model::Data& d = *s.data;
        VoxelState& v = s.voxels;
        int passes = 0;
        if (d.poisson.active) {
            // A split d is an internal variable each step relaxes once; the slow modes see it
            // relaxed, so it is converged here (frozen it would be stiffer than the body).
            const int limit = d.poisson.pair_voxels.empty() ? 1 : max_relaxations_;
            std::array<std::vector<float>, 3> before;
            for (passes = 1; passes <= limit; ++passes) {
                for (int a = 0; a < 3; ++a)
                    before[static_cast<std::size_t>(a)].assign(s.poisson.pair_last[a],
                                                               s.poisson.pair_last[a] + d.stored);
                poisson_pass(d, v, s.links, s.poisson, 0.0f, 0.0f);
                if (limit == 1) break;
                float change = 0.0f;
                for (int a = 0; a < 3; ++a)
                    for (int c = 0; c < d.stored; ++c)
                        change = std::max(
                            change,
                            std::fabs(
                                s.poisson.pair_last[a][c] -
                                before[static_cast<std::size_t>(a)][static_cast<std::size_t>(c)]));
                if (change <= 1e-9f) break;
            }
        }
        // Twice where the passes hold a lagged rate (explicit bond damping, edge springs'
        // gaps): the second sees no change, so no damping load, only the elastic one.
        const int link_rounds = d.implicit_sweeps > 0 ? 1 : 2;
        for (int round = 0; round < link_rounds; ++round)
            for (int a = 0; a < 3; ++a)
                link_pass(d, v, s.links[a], d.poisson.active ? &s.poisson : nullptr, a, 0.0f, 0.0f);
        const bool springs = d.edge_springs.size() > 0;
        for (int i = 0; i < 3; ++i) {
            std::fill(v.vel[i].begin(), v.vel[i].end(), 0.0);
            std::fill(v.omega[i].begin(), v.omega[i].end(), 0.0);
            if (d.implicit_sweeps > 0) {
                std::fill(v.vel_delta[i].begin(), v.vel_delta[i].end(), 0.0);
                std::fill(v.omega_delta[i].begin(), v.omega_delta[i].end(), 0.0);
            }
        }
        if (springs) {
            edge_pass(d, v, s.edges, 0.0, 0.0);
            for (int i = 0; i < 3; ++i)
                std::fill(v.omega[i].begin(), v.omega[i].end(), 0.0);
            edge_pass(d, v, s.edges, 0.0, 0.0);
        }
        VoxelPassInput in;
        if (springs) in.applied_force = &s.edges.force;
        in.gravity_m_s2 = d.spec.environment.gravity_m_s2;
        in.floor_z = -1e300;
        in.velocity_only = true;
        // The explicit path moves the pose; run it on a copy of the pose so the probe's stays.
        const auto pos = v.pos;
        const auto quat = v.quat;
        const auto quat_f = v.quat_f;
        voxel_pass(d, v, s.links, in);
        v.pos = pos;
        v.quat = quat;
        v.quat_f = quat_f;
        const auto& lin = d.implicit_sweeps > 0 ? v.vel_star : v.vel;
        const auto& ang = d.implicit_sweeps > 0 ? v.omega_star : v.omega;
        out.assign(static_cast<std::size_t>(d.voxels), {});
        for (int c = 0; c < d.voxels; ++c) {
            auto& f = out[static_cast<std::size_t>(c)];
            const double keep = d.linear_keep[c] * d.movable[c];
            for (int i = 0; i < 3; ++i) {
                f[static_cast<std::size_t>(i)] = keep > 0.0 && d.dt_inv_mass[c] > 0.0
                                                     ? lin[i][c] / (keep * d.dt_inv_mass[c])
                                                     : 0.0;
                const double turn = d.angular_keep[i][c];
                f[static_cast<std::size_t>(3 + i)] = turn > 0.0 && d.dt_inv_inertia[c] > 0.0
                                                         ? ang[i][c] / (turn * d.dt_inv_inertia[c])
                                                         : 0.0;
            }
        }
        return std::max(passes, 1);
    }

  private:
    World::State& probe_;
    const World::State& base_;
    int max_relaxations_;
};

}  // namespace

struct LinearisedBody::Impl {
    bool ok = false;
    std::string reason;
    int force_evaluations = 0, relaxations = 0;
    double margin = 0.0, leak = 0.0, beta_max = 0.0, c_min = 0.0;
    std::array<double, 4> block_margin{};  //!< margin_s2 of the blocks (move, turn) x (move, turn)
    Sparse K;                     //!< symmetrised, lower and upper
    std::vector<double> mass;     //!< per dof (kg; kg m^2)
    std::vector<double> damping;  //!< per dof, c_i / m_i (1/s)
    Eigen::SimplicialLDLT<Sparse, Eigen::Lower, Eigen::AMDOrdering<int>> ldlt;
    bool analysed = false;

    //! True when K_s times k_scale plus diag(mass_i shift_i) is positive definite.
    bool positive(double k_scale, const std::vector<double>& shift) {
        Sparse A = k_scale * K;
        for (int i = 0; i < A.rows(); ++i)
            A.coeffRef(i, i) +=
                mass[static_cast<std::size_t>(i)] * shift[static_cast<std::size_t>(i)];
        if (!analysed) {
            ldlt.analyzePattern(A);
            analysed = true;
        }
        ldlt.factorize(A);
        if (ldlt.info() != Eigen::Success) return false;
        const auto D = ldlt.vectorD();
        for (int i = 0; i < D.size(); ++i)
            if (!(D[i] > 0.0)) return false;
        return true;
    }
};

const World::State& LinearisedBody::state_of(const World& world) {
    return *world.state_;
}
World::State& LinearisedBody::state_of(World& world) {
    return *world.state_;
}

LinearisedBody::~LinearisedBody() = default;
LinearisedBody::LinearisedBody(LinearisedBody&&) noexcept = default;
LinearisedBody& LinearisedBody::operator=(LinearisedBody&&) noexcept = default;

LinearisedBody::LinearisedBody(const World& world, const Options& options)
    : impl_(std::make_unique<Impl>()) {
    Impl& m = *impl_;
    const World::State& base = state_of(world);
    const Model::Data& d = *base.data;
    const Model& model = world.model();
    if (world.diverged()) {
        m.reason = "the world diverged";
        return;
    }
    // Linearised about rest before the drive starts: the passes run at phase 0.
    const bool driven =
        d.muscle.signals > 0 || (d.any_active && world.time_s() >= d.spec.actuation.start_s);
    if (driven) {
        m.reason = "the drive has started (the rest pose is linearised before it)";
        return;
    }
    const int n = d.voxels;
    const double L = d.voxel_size_m;
    // Degrees of freedom: a voxel's translation where it moves, its turn about each world axis
    // where it may turn (a held voxel's clamp: model.cpp).
    std::vector<std::array<int, 6>> dof(static_cast<std::size_t>(n));
    int count = 0;
    for (int v = 0; v < n; ++v) {
        auto& f = dof[static_cast<std::size_t>(v)];
        const double inertia = d.rotary_inertia_scale * d.mass[v] * L * L / 6.0;
        for (int i = 0; i < 6; ++i) {
            const bool moves = i < 3
                                   ? d.dt_inv_mass[v] > 0.0 && d.linear_keep[v] * d.movable[v] > 0.0
                                   : d.angular_keep[i - 3][v] > 0.0 && d.dt_inv_inertia[v] > 0.0;
            f[static_cast<std::size_t>(i)] = moves ? count++ : -1;
            if (!moves) continue;
            const double keep = i < 3 ? d.linear_keep[v] : d.angular_keep[i - 3][v];
            m.mass.push_back(i < 3 ? d.mass[v] : inertia);
            m.damping.push_back((1.0 / keep - 1.0) / d.dt_s);
        }
    }
    if (count == 0) {
        m.reason = "nothing moves";
        return;
    }
    m.c_min = *std::min_element(m.damping.begin(), m.damping.end());

    // The colouring: voxels whose lattice coordinates agree modulo p = 2 reach + 1 are at least
    // p apart along some axis, so no voxel lies within `reach` of two of them.
    const int R = std::max(1, options.reach);
    const int p = 2 * R + 1;
    std::map<std::array<int, 3>, int> at;
    std::vector<std::array<int, 3>> coords(static_cast<std::size_t>(n));
    for (int v = 0; v < n; ++v) {
        coords[static_cast<std::size_t>(v)] = model.voxel_coords(v);
        at.emplace(coords[static_cast<std::size_t>(v)], v);
    }
    auto colour = [&](int v) {
        const auto& c = coords[static_cast<std::size_t>(v)];
        return ((c[0] % p) * p + (c[1] % p)) * p + (c[2] % p);
    };

    World scratch(base.model);
    ForceProbe probe(state_of(scratch), base, options.max_relaxations);
    std::vector<std::array<double, 6>> plus, minus;
    std::vector<Eigen::Triplet<double>> entries;
    std::vector<int> near(static_cast<std::size_t>(n), -1);  // the moved voxel within reach
    double inside = 0.0, outside = 0.0;
    for (int col = 0; col < p * p * p; ++col) {
        std::vector<int> moved;
        for (int v = 0; v < n; ++v)
            if (colour(v) == col) moved.push_back(v);
        for (int type = 0; type < 6; ++type) {
            std::vector<int> these;
            for (int v : moved)
                if (dof[static_cast<std::size_t>(v)][static_cast<std::size_t>(type)] >= 0)
                    these.push_back(v);
            if (these.empty()) continue;
            const double h = type < 3 ? options.translation_step * L : options.rotation_step;
            for (int sign = 1; sign >= -1; sign -= 2) {
                probe.reset();
                VoxelState& s = probe.state().voxels;
                for (int v : these) {
                    if (type < 3) {
                        s.pos[type][v] += sign * h;
                        continue;
                    }
                    // A turn by sign h about world axis `type - 3`: q' = (1, a/2) q, normalised.
                    double w[3] = {0.0, 0.0, 0.0};
                    w[type - 3] = sign * h;
                    const double qw = s.quat[0][v], qx = s.quat[1][v], qy = s.quat[2][v],
                                 qz = s.quat[3][v];
                    double q[4] = {qw - 0.5 * (w[0] * qx + w[1] * qy + w[2] * qz),
                                   qx + 0.5 * (qw * w[0] + w[1] * qz - w[2] * qy),
                                   qy + 0.5 * (qw * w[1] + w[2] * qx - w[0] * qz),
                                   qz + 0.5 * (qw * w[2] + w[0] * qy - w[1] * qx)};
                    const double norm =
                        std::sqrt(q[0] * q[0] + q[1] * q[1] + q[2] * q[2] + q[3] * q[3]);
                    for (int i = 0; i < 4; ++i) {
                        s.quat[i][v] = q[i] / norm;
                        s.quat_f[i][v] = static_cast<float>(s.quat[i][v]);
                    }
                }
                m.relaxations = std::max(m.relaxations, probe.forces(sign > 0 ? plus : minus));
                ++m.force_evaluations;
            }
            for (int v : these) {
                const auto& c = coords[static_cast<std::size_t>(v)];
                for (int dx = -R; dx <= R; ++dx)
                    for (int dy = -R; dy <= R; ++dy)
                        for (int dz = -R; dz <= R; ++dz) {
                            const auto it = at.find({c[0] + dx, c[1] + dy, c[2] + dz});
                            if (it != at.end()) near[static_cast<std::size_t>(it->second)] = v;
                        }
            }
            const int column_type = type;
            for (int u = 0; u < n; ++u) {
                const int v = near[static_cast<std::size_t>(u)];
                for (int e = 0; e < 6; ++e) {
                    const double change =
                        plus[static_cast<std::size_t>(u)][static_cast<std::size_t>(e)] -
                        minus[static_cast<std::size_t>(u)][static_cast<std::size_t>(e)];
                    if (v < 0) {
                        outside = std::max(outside, std::fabs(change));
                        continue;
                    }
                    inside = std::max(inside, std::fabs(change));
                    const int row = dof[static_cast<std::size_t>(u)][static_cast<std::size_t>(e)];
                    const int column =
                        dof[static_cast<std::size_t>(v)][static_cast<std::size_t>(column_type)];
                    if (row < 0 || change == 0.0) continue;
                    entries.emplace_back(row, column, -change / (2.0 * h));
                }
                near[static_cast<std::size_t>(u)] = -1;
            }
        }
    }
    m.leak = inside > 0.0 ? outside / inside : 0.0;

    // The floor's penalty spring under the voxels that touch it (voxel_pass.cpp), and its
    // dashpot's ratio to it; friction is left out (a sliding voxel is softer than a stuck one).
    const double floor_z = d.spec.environment.floor ? -d.origin_m[2] : -1e300;
    for (int v = 0; v < n; ++v) {
        const int z = dof[static_cast<std::size_t>(v)][2];
        if (z < 0 || !(0.5 * L - (base.voxels.pos[2][v] - floor_z) > 0.0)) continue;
        entries.emplace_back(z, z, d.floor_k[v]);
        if (d.floor_k[v] > 0.0) m.beta_max = std::max(m.beta_max, d.floor_c[v] / d.floor_k[v]);
    }
    // The dashpots beside the springs: links (Rayleigh beta), edge springs (c / k, at their
    // softer direction).
    for (int a = 0; a < 3; ++a) {
        const LinkParams& lp = d.links[static_cast<std::size_t>(a)];
        for (int c = 0; c < d.slots; ++c) {
            if (lp.exists[static_cast<std::size_t>(c)] == 0.0f) continue;
            const double beta = d.implicit_sweeps > 0
                                    ? lp.damp_beta[static_cast<std::size_t>(c)]
                                    : lp.damp_steps[static_cast<std::size_t>(c)] * d.dt_s;
            m.beta_max = std::max(m.beta_max, beta);
        }
    }
    const auto& e = d.edge_springs;
    for (int i = 0; i < e.size(); ++i) {
        const double k = std::min(e.k_across[static_cast<std::size_t>(i)],
                                  e.k_along[static_cast<std::size_t>(i)]);
        if (k > 0.0)
            m.beta_max = std::max(m.beta_max, e.damping[static_cast<std::size_t>(i)] * d.dt_s / k);
    }

    Sparse K(count, count);
    K.setFromTriplets(entries.begin(), entries.end());
    Sparse Kt = K.transpose();
    m.K = 0.5 * (K + Kt);
    // The antisymmetric part's norm in M's units: for S = M^-1/2 (K - K^T) / 2 M^-1/2, whose
    // absolute values are symmetric, ||S||_2 <= its largest absolute row sum.
    Sparse skew = 0.5 * (K - Kt);
    std::vector<double> rows(static_cast<std::size_t>(count), 0.0);
    // The same sums per block (turns or not, of the row and of the column): where it comes from.
    std::vector<std::array<double, 4>> block_rows(static_cast<std::size_t>(count),
                                                  std::array<double, 4>{});
    std::vector<int> turn(static_cast<std::size_t>(count), 0);
    for (int v = 0; v < n; ++v)
        for (std::size_t i = 3; i < 6; ++i) {
            const int j = dof[static_cast<std::size_t>(v)][i];
            if (j >= 0) turn[static_cast<std::size_t>(j)] = 1;
        }
    for (int k = 0; k < skew.outerSize(); ++k)
        for (Sparse::InnerIterator it(skew, k); it; ++it) {
            const auto r = static_cast<std::size_t>(it.row());
            const auto c = static_cast<std::size_t>(it.col());
            const double a = std::fabs(it.value()) / std::sqrt(m.mass[r] * m.mass[c]);
            rows[r] += a;
            block_rows[r][static_cast<std::size_t>(2 * turn[r] + turn[c])] += a;
        }
    m.margin = *std::max_element(rows.begin(), rows.end());
    for (const auto& r : block_rows)
        for (std::size_t b = 0; b < 4; ++b)
            m.block_margin[b] = std::max(m.block_margin[b], r[b]);
    m.ok = true;
}

bool LinearisedBody::ok() const {
    return impl_->ok;
}
const std::string& LinearisedBody::reason() const {
    return impl_->reason;
}
int LinearisedBody::dofs() const {
    return static_cast<int>(impl_->mass.size());
}
int LinearisedBody::force_evaluations() const {
    return impl_->force_evaluations;
}
int LinearisedBody::relaxations() const {
    return impl_->relaxations;
}
double LinearisedBody::margin_s2() const {
    return impl_->margin;
}
double LinearisedBody::block_margin_s2(bool row_turns, bool column_turns) const {
    return impl_->block_margin[static_cast<std::size_t>(2 * row_turns + column_turns)];
}
double LinearisedBody::leak() const {
    return impl_->leak;
}
double LinearisedBody::beta_max_s() const {
    return impl_->beta_max;
}
double LinearisedBody::damping_min_per_s() const {
    return impl_->c_min;
}

bool LinearisedBody::stiffer_than(double sigma_s2) const {
    if (!impl_->ok) return false;
    std::vector<double> shift(impl_->mass.size(), -sigma_s2);
    return impl_->positive(1.0, shift);
}

double LinearisedBody::lowest_frequency_bound(double upper_rad_s, int bisections) const {
    double lo = 0.0, hi = upper_rad_s;
    if (!stiffer_than(0.0)) return 0.0;
    for (int i = 0; i < bisections; ++i) {
        const double mid = 0.5 * (lo + hi);
        (stiffer_than(mid * mid) ? lo : hi) = mid;
    }
    return lo;
}

bool LinearisedBody::decays_at_least(double alpha) const {
    const Impl& m = *impl_;
    if (!m.ok) return false;
    if (!(alpha > 0.0)) return stiffer_than(0.0);
    // Per mode (z the eigenvector, every quantity over z*Mz): mu = lambda + alpha solves
    // mu^2 + b mu + p + i q = 0 with b = c - 2 alpha >= c_min - 2 alpha, |q| <= margin (the
    // antisymmetric part) and p >= (1 - alpha beta_max) k_s - alpha c_g + alpha^2. Such a root
    // reaches Re mu = 0 only where p = q^2 / b^2, so Re mu < 0 for all of them when p exceeds
    // margin^2 / (c_min - 2 alpha)^2 for every z: A below positive definite.
    const double b = m.c_min - 2.0 * alpha;
    if (!(b > 0.0)) return false;
    const double scale = 1.0 - alpha * m.beta_max;
    if (!(scale > 0.0)) return false;
    const double circulation = m.margin * m.margin / (b * b);
    std::vector<double> shift(m.mass.size());
    for (std::size_t i = 0; i < shift.size(); ++i)
        shift[i] = -alpha * m.damping[i] + alpha * alpha - circulation;
    return impl_->positive(scale, shift);
}

DecayProof LinearisedBody::prove_decay(double period_s, double target) const {
    DecayProof proof;
    if (!impl_->ok) {
        proof.reason = impl_->reason;
        return proof;
    }
    if (!(period_s > 0.0) || !(target > 0.0 && target < 1.0)) {
        proof.reason = "no period or no target";
        return proof;
    }
    if (!decays_at_least(-std::log(target) / period_s)) {
        proof.reason = "a linear mode may decay slower than the target";
        return proof;
    }
    proof.proven = true;
    proof.decay_per_period = target;
    return proof;
}

}  // namespace bhm::engine
