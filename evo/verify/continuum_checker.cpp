#include "evo/verify/continuum_checker.hpp"

#include <filesystem>
#include <stdexcept>

#include "engine/io/staged_folder.hpp"
#include "evo/experiment/body_spec_of.hpp"
#include "evo/verify/ccx_run.hpp"
#include "evo/verify/verify_report.hpp"

namespace bhm::evo {

CalculixChecker::CalculixChecker(VerifyOptions options) : options_(std::move(options)) {
    options_.threads = 1;
    options_.nonlinear_from_coarse_mesh = true;  // several times quicker (docs/verify.md)
    // The second continuum law only where the first does not agree, Neo-Hookean first: the
    // same verdict as with both, one nonlinear solve fewer where it agrees (docs/verify.md).
    options_.second_law_only_where_first_differs = true;
    options_.first_law = FemMaterialLaw::NeoHookean;
}

std::string CalculixChecker::unavailable() const {
    return ccx_available() ? ""
                           : "CalculiX (ccx) is not on the PATH; install the Debian package "
                             "calculix-ccx, or set evolution.verify.every_generations to 0";
}

LoopCheck loop_check_of(const BodyVerification& v) {
    LoopCheck c;
    if (v.status != VerifyStatus::Compared) {
        c.outcome = LoopCheckOutcome::OutOfReach;
        c.verdict = v.verdict();
        return c;
    }
    c.outcome = v.agrees ? LoopCheckOutcome::Agrees : LoopCheckOutcome::Differs;
    c.worst = v.worst;
    c.fem_score = v.fem_score;
    c.engine_score = v.engine_score;
    c.verdict = v.verdict();
    if (!v.material_law.empty()) c.laws.push_back(v.material_law);
    if (!v.other_law.empty() && !v.other_law_skipped) c.laws.push_back(v.other_law);
    return c;
}

std::optional<LoopCheck> CalculixChecker::check(const Experiment& rules,
                                                const LoopCheckRequest& body,
                                                const std::string& out_dir,
                                                const std::atomic<bool>& cancel) {
    VerifyOptions options = options_;
    options.tolerance = rules.evolution.verify.tolerance;
    options.control.cancel = &cancel;
    BodyVerification v;
    try {
        v = verify_body(make_body_spec(rules, body.body), rules.fitness.measure, options);
    } catch (const VerifyCancelled&) {
        return std::nullopt;
    } catch (const std::exception& e) {
        LoopCheck failed;
        failed.outcome = LoopCheckOutcome::Failed;
        failed.verdict = e.what();
        return failed;
    }
    if (!out_dir.empty()) {
        const auto dir = std::filesystem::path(out_dir) / "verify" /
                         ("individual-" + std::to_string(body.id));
        // Staged and swapped in whole (issue 41 R5): a kill part way leaves the studio the old
        // complete check or the new one, never new meshes beside an old report. The folder is
        // refused when it holds anything a verification does not write.
        engine::StagedFolder staged(dir.string(), is_verification_file);
        try {
            write_verification(v, options, staged.staging());
        } catch (const std::exception& e) {
            throw std::runtime_error(staged.as_final(e.what()));
        }
        staged.commit();
    }
    return loop_check_of(v);
}

}  // namespace bhm::evo
