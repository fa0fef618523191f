// "Verify in FEM": the actions of the Analysis > FEM tab (its Kept FEM reports list too) and the
// Champions and Population lists, and the per-frame hand-off from the verifier's worker
// (app/gui/session/fem_verifier.hpp, docs/studio.md).
#include <algorithm>
#include <cstdio>
#include <memory>
#include <string>

#include "app/gui/actions/studio_actions.hpp"
#include "evo/run/checkpoint.hpp"

namespace bhm::app::gui {

namespace {

bool start_verification(Studio& studio, FemVerifyRequest request) {
    if (studio.verify.worker.running()) {
        set_status(studio, "a verification is running: cancel it first", true);
        return false;
    }
    if (request.run_dir.empty()) {
        set_status(studio,
                   "verify in FEM: the body belongs to no run directory to keep the report in",
                   true);
        return false;
    }
    const std::string label = request.label;
    studio.verify.worker.start(std::move(request));
    const auto state = studio.verify.worker.state();
    if (state && state->phase == FemVerifyPhase::Failed) {
        set_status(studio, "verify in FEM: " + state->error, true);
        return false;
    }
    set_status(studio, "verifying " + label + " in FEM (CalculiX)");
    return true;
}

}  // namespace

bool verify_shown_body(Studio& studio) {
    if (!studio.bodies.shown || !studio.bodies.shown->framed_body) {
        set_status(studio, "verify in FEM: select a champion or an individual first", true);
        return false;
    }
    FemVerifyRequest request;
    request.id = studio.bodies.shown->id;
    request.label = studio.bodies.shown->label;
    request.experiment = studio.bodies.shown->experiment;
    request.framed_body = studio.bodies.shown->framed_body;
    request.run_dir = studio.run.snapshot ? studio.run.snapshot->run_dir : "";
    return start_verification(studio, std::move(request));
}

bool verify_champion(Studio& studio, const ChampionEntry& entry) {
    if (!studio.run.snapshot) return false;
    if (studio.verify.worker.running()) {
        set_status(studio, "a verification is running: cancel it first", true);
        return false;
    }
    if (!replay_champion(studio, entry, false)) return false;
    try {
        SimulationRequest champion = champion_request(studio, entry);
        FemVerifyRequest request;
        request.id = champion.id;
        request.label = std::move(champion.label);
        request.experiment = std::move(champion.experiment);
        request.framed_body = std::move(champion.framed_body);
        request.run_dir = studio.run.snapshot->run_dir;
        return start_verification(studio, std::move(request));
    } catch (const std::exception& e) {
        set_status(studio, e.what(), true);
        return false;
    }
}

bool verify_individual(Studio& studio, std::int64_t id) {
    if (!studio.run.snapshot) return false;
    if (studio.verify.worker.running()) {
        set_status(studio, "a verification is running: cancel it first", true);
        return false;
    }
    // The member's own framed body, as its row simulates it; select_individual says why not.
    const auto run =
        studio.run.snapshot;  // held: the snapshot outlives a newer one taken meanwhile
    const auto it = std::find_if(run->population.begin(), run->population.end(),
                                 [id](const PopulationMember& m) { return m.id == id; });
    if (!select_individual(studio, id) || it == run->population.end() || !it->body) return false;
    const PopulationMember& m = *it;
    FemVerifyRequest request;
    request.id = id;
    request.label =
        "individual #" + std::to_string(id) + " of generation " + std::to_string(run->generation);
    request.experiment = run->experiment;
    request.framed_body = m.body;
    request.run_dir = run->run_dir;
    return start_verification(studio, std::move(request));
}

bool show_kept_verification(Studio& studio, std::int64_t id) {
    if (!studio.run.snapshot) return false;
    const auto run =
        studio.run.snapshot;  // held: the snapshot outlives a newer one taken meanwhile
    // The member's body as its row or champion file holds it; the report follows the body
    // shown (update_verification reads it), so nothing is solved.
    if (run->has_champion && run->champion.id == id) return select_individual(studio, id);
    for (const auto& m : run->population)
        if (m.id == id && m.body) return select_individual(studio, id);
    for (const auto& e : studio.run.champion_history.entries())
        if (e.id == id) return replay_champion(studio, e, false);
    // A reopened run directory lists only its champions: the population is in the checkpoint.
    try {
        const auto loaded = evo::load_checkpoint(run->run_dir);
        const auto& state = loaded.state;
        const evo::Individual* found = nullptr;
        for (const auto& m : state.population)
            if (m.id == id) found = &m;
        if (!found && state.champion && state.champion->individual.id == id)
            found = &state.champion->individual;
        if (!found) {
            set_status(studio,
                       "individual #" + std::to_string(id) +
                           " is neither among the champions nor in the population of " +
                           loaded.path + " (generation " + std::to_string(state.generation) +
                           "): its kept report has no body to be shown on",
                       true);
            return false;
        }
        SimulationRequest request;
        request.id = id;
        request.label = "individual #" + std::to_string(id) + " of generation " +
                        std::to_string(state.generation) + " (checkpoint)";
        request.experiment = run->experiment;
        request.framed_body = std::make_shared<const evo::Body>(found->phenotype.body);
        studio.bodies.follow_champion = false;
        studio.run.selected_id = id;
        studio.bodies.simulator.request(std::move(request));
        set_status(studio, "simulating individual #" + std::to_string(id) +
                               " from the checkpoint, with its kept FEM report");
        return true;
    } catch (const std::exception& e) {
        set_status(studio, e.what(), true);
        return false;
    }
}

void cancel_verification(Studio& studio) {
    if (!studio.verify.worker.running()) return;
    studio.verify.worker.cancel();
    set_status(studio, "cancelling the verification");
}

std::string fem_verdict_line(const FemVerification& v) {
    // Verdicts since issue 40 state their tolerance themselves; older kept reports do not.
    if (!v.compared || v.verdict.find("(tolerance ") != std::string::npos) return v.verdict;
    char tolerance[48];
    std::snprintf(tolerance, sizeof tolerance, " (tolerance %.3g %%)", 100.0 * v.tolerance);
    return v.verdict + tolerance;
}

void update_verification(Studio& studio) {
    if (studio.verify.worker.version() != studio.verify.state_version) {
        studio.verify.state_version = studio.verify.worker.version();
        studio.verify.state = studio.verify.worker.state();
        const auto& st = studio.verify.state;
        // Each job's end once, even when it started and ended between two frames.
        if (st && st->phase != FemVerifyPhase::Running && st->job != studio.verify.job_reported) {
            studio.verify.job_reported = st->job;
            char seconds[32];
            std::snprintf(seconds, sizeof seconds, "%.1f s", st->elapsed_s);
            if (st->phase == FemVerifyPhase::Finished && st->result) {
                if (studio.bodies.shown && studio.bodies.shown->id == st->id) {
                    studio.verify.result = st->result;
                    studio.verify.kept_error.clear();
                    studio.verify.load =
                        std::min<int>(1, static_cast<int>(st->result->rows.size()) - 1);
                }
                set_status(studio, st->label + ": " + fem_verdict_line(*st->result) + ", " +
                                       seconds);
            } else if (st->phase == FemVerifyPhase::Cancelled) {
                set_status(studio, "verification of " + st->label + " cancelled after " + seconds +
                                       "; nothing was written");
            } else if (st->phase == FemVerifyPhase::Failed) {
                set_status(studio, "verify in FEM: " + st->error, true);
            }
        }
    }
    // A body newly shown: the report kept for it in its run directory, if any.
    const std::string run_dir = studio.run.snapshot ? studio.run.snapshot->run_dir : "";
    // The reports kept in that run directory: listed again when another run is shown or a
    // verification has ended (it may have added one).
    const std::string kept_key = run_dir + "#" + std::to_string(studio.verify.job_reported);
    if (kept_key != studio.verify.kept_reports_key) {
        studio.verify.kept_reports_key = kept_key;
        studio.verify.kept_reports = kept_verifications(run_dir);
    }
    const std::string key = studio.bodies.shown && !run_dir.empty()
                                ? run_dir + "#" + std::to_string(studio.bodies.shown->id)
                                : "";
    if (key == studio.verify.result_key) return;
    studio.verify.result_key = key;
    studio.verify.result.reset();
    studio.verify.kept_error.clear();
    if (key.empty()) return;
    try {
        auto kept = read_verification(verification_dir(run_dir, studio.bodies.shown->id),
                                      studio.bodies.shown->id);
        if (kept) {
            studio.verify.result = std::make_shared<const FemVerification>(std::move(*kept));
            studio.verify.load =
                std::min<int>(1, static_cast<int>(studio.verify.result->rows.size()) - 1);
        }
    } catch (const std::exception& e) {
        studio.verify.kept_error = e.what();
    }
}

}  // namespace bhm::app::gui
