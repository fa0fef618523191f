#include "evo/verify/continuum_checker.hpp"

#include <filesystem>
#include <stdexcept>

#include "evo/experiment/body_spec_of.hpp"
#include "evo/verify/ccx_run.hpp"
#include "evo/verify/verify_report.hpp"

namespace bhm::evo {

CalculixChecker::CalculixChecker(VerifyOptions options) : options_(std::move(options)) {
    options_.threads = 1;
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
        write_verification(v, options, dir.string());
    }
    return loop_check_of(v);
}

}  // namespace bhm::evo
