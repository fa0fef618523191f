#pragma once
// The linearised body at rest, and the decay of its motion it proves (issue 42; docs/physics.md,
// "A proven decay bound of a held body").
//
// From a World at rest before actuation starts: the stiffness K = -dF/dx of the engine's own
// elastic forces (links, Poisson coupling with its relaxed splits d relaxed until a pass moves
// none by 1e-9, which on Poisson bodies stops short of converged: docs/physics.md; edge springs,
// gravity's prestress, a held voxel's clamp spring) by central differences, every voxel of one
// colour of a (2 reach + 1)^3 lattice colouring moved at once (6 x 125 pairs of force evaluations
// at reach 2, not 6 N), the floor's penalty spring under the voxels that touch it added as built
// (friction left out: a voxel free to slide is softer than a stuck one), the masses and inertias M
// of the moving degrees of freedom and the per-voxel global damping C_g (c_i / m_i from the
// model's implicit factor). K_s is K's symmetric part; its antisymmetric part (the finite
// differences' error and any non-conservative part of the forces) is bounded in M's units by its
// largest absolute row sum, `margin`.
//
// What it proves, for M x'' + C x' + K x = 0 with C = C_g + C_b, C_g = diag(c_i m_i), and C_b
// the bond, edge-spring and floor dashpots, each beta <= beta_max times its own spring (the
// engine's Rayleigh form), so C_b <= beta_max K_s: for every eigenvalue lambda with eigenvector z
// (quantities over z*Mz), lambda^2 + c lambda + k_s + i k_a = 0, c >= c_min, |k_a| <= margin.
// With mu = lambda + alpha: mu^2 + b mu + p + i q = 0, b = c - 2 alpha, p = k_s - alpha c +
// alpha^2, and a root crosses Re mu = 0 only where p = q^2 / b^2. So if alpha < c_min / 2 and
// A = (1 - alpha beta_max) K_s - alpha C_g + (alpha^2 - margin^2 / (c_min - 2 alpha)^2) M is
// positive definite (every pivot of its sparse LDLT > 0, Sylvester's law of inertia), every mode
// decays at least as exp(-alpha t). Not covered: the symmetric part of the finite differences'
// error (its antisymmetric part measures its size), actuation (the orbit is not the rest pose),
// contact changes, friction and the integrator; the early end's corpus gate covers them.
#include <memory>
#include <string>

#include "engine/world.hpp"

namespace bhm::engine {

//! What LinearisedBody::prove_decay proved.
struct DecayProof {
    bool proven = false;
    //! The bound on the decay per period of every linear mode: the target when proven, else 1.
    double decay_per_period = 1.0;
    std::string reason;  //!< why it is not proven (empty when it is)
};

class LinearisedBody {
  public:
    struct Options {
        double translation_step = 2e-3;  //!< finite-difference step, in voxel lengths
        double rotation_step = 2e-3;     //!< rad
        int reach = 2;  //!< voxels (Chebyshev) over which one voxel's move changes forces
        int max_relaxations = 400;  //!< Poisson passes to converge the split d at each pose
    };

    //! Assembles the model of the world's body at its current pose. It must be at rest before
    //! its actuation starts (or the engine has nothing to linearise about): otherwise, or when a
    //! part of it is not held, ok() is false and reason() says why. The world is not changed.
    explicit LinearisedBody(const World& world, const Options& options);
    explicit LinearisedBody(const World& world) : LinearisedBody(world, Options{}) {}
    ~LinearisedBody();
    LinearisedBody(LinearisedBody&&) noexcept;
    LinearisedBody& operator=(LinearisedBody&&) noexcept;

    bool ok() const;
    const std::string& reason() const;
    int dofs() const;               //!< moving degrees of freedom
    int force_evaluations() const;  //!< the engine's force passes it ran
    int relaxations() const;        //!< the most Poisson passes one pose needed
    //! Bound of the norm of M^-1/2 (K - K^T) / 2 M^-1/2 (s^-2).
    double margin_s2() const;
    //! The same bound over one block of rows and columns (a voxel's move or its turn): which
    //! couplings the antisymmetric part sits in.
    double block_margin_s2(bool row_turns, bool column_turns) const;
    //! The largest force change seen farther than `reach` from every moved voxel, over the
    //! largest seen within it: the colouring's check (0 when the reach holds everything).
    double leak() const;
    double beta_max_s() const;         //!< largest dashpot over its spring (s)
    double damping_min_per_s() const;  //!< smallest c_i / m_i of the global damping
    //! True when K_s - sigma M is positive definite: the lowest angular frequency of the
    //! undamped linear body (K's symmetric part) exceeds sqrt(sigma).
    bool stiffer_than(double sigma_s2) const;
    //! A proven lower bound on the lowest angular frequency (rad/s) by bisection on stiffer_than
    //! between 0 and upper_rad_s (0 when not even the smallest is proven).
    double lowest_frequency_bound(double upper_rad_s, int bisections) const;
    //! True when every mode of the linear damped body decays at least as exp(-alpha t).
    bool decays_at_least(double alpha_per_s) const;
    //! Proves that every mode decays by at least `target` (0 < target < 1) per period_s.
    DecayProof prove_decay(double period_s, double target) const;

  private:
    static const World::State& state_of(const World& world);
    static World::State& state_of(World& world);
    struct Impl;
    std::unique_ptr<Impl> impl_;
};

}  // namespace bhm::engine
