#pragma once
// The CalculiX checker of the evolution loop (evolution.verify; evo/run/loop_check.hpp): one body
// verified as `bhm verify` does (verify_body: the FEM and our engine's quasi-static answer at
// rest, +A and -A, judged on the experiment's measure), except that nonlinear steps take their
// nonlinear part from a coarse mesh (coarse_nonlinearity.hpp: several times quicker, as bhm
// verify --coarse-nonlinearity), its files kept where the studio finds them,
// RUN_DIR/verify/individual-<id>/ (report.json, shapes.json, the FEM's meshes).
#include <memory>

#include "evo/run/loop_check.hpp"
#include "evo/verify/verify_body.hpp"

namespace bhm::evo {

class CalculixChecker : public ContinuumChecker {
  public:
    //! options: the mesh, geometry and limits of every check (tolerance comes from the run's
    //! evolution.verify; control is set per check). One ccx thread: the checks run beside the
    //! run's simulations, and a single-threaded solve is the one that repeats bit for bit.
    explicit CalculixChecker(VerifyOptions options = {});
    std::optional<LoopCheck> check(const Experiment& rules, const LoopCheckRequest& body,
                                   const std::string& out_dir,
                                   const std::atomic<bool>& cancel) override;
    std::string unavailable() const override;

  private:
    VerifyOptions options_;
};

//! The loop's record of one verification (no timings: they do not repeat).
LoopCheck loop_check_of(const BodyVerification& v);

}  // namespace bhm::evo
