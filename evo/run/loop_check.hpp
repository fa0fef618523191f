#pragma once
// Continuum checks inside the evolution loop (evolution.verify; docs/verify.md, "CalculiX in the
// evolution loop"): which bodies are checked after a generation, what a check's result does to a
// member under the run's policy, and the job that runs the checks on a thread of its own beside
// the next generation's simulations.
//
// The run loop knows checks only through ContinuumChecker; the CalculiX one lives in evo/verify/
// (continuum_checker.hpp, after run/ in evo's order) and the front ends hand it in
// (RunOptions::checker), as they hand in an Evaluator.
//
// Determinism: the bodies checked after generation g are a pure function of the state committed
// at g; they are picked at the beginning of generation g + 1 and kept in the state from its
// commit on (PendingChecks), so a run resumed anywhere before they land starts the same checks;
// they are always joined before the selection of generation g + N (N = every_generations), and a
// check's figures are those of a deterministic solve. A change of rules before they land drops
// them (they were made for the old rules), in the uninterrupted and the resumed run alike. So a
// run with checks, stopped and resumed, is the uninterrupted run bit for bit.
#include <atomic>
#include <cstdint>
#include <memory>
#include <optional>
#include <string>
#include <thread>
#include <unordered_map>
#include <vector>

#include "evo/experiment/experiment.hpp"
#include "evo/search/individual.hpp"

namespace bhm::evo {

enum class LoopCheckOutcome { Agrees, Differs, OutOfReach, Failed };
inline constexpr std::array<const char*, 4> kLoopCheckOutcomeNames = {"agrees", "differs",
                                                                      "out_of_reach", "failed"};

//! One body checked in the loop. Only figures that a repeated solve reproduces exactly (no
//! timings): they are part of the run's state.
struct LoopCheck {
    int generation = 0;     //!< the generation whose population it was picked from
    std::int64_t id = 0;    //!< the individual checked (its phenotype may recur under other ids)
    std::uint64_t hash = 0; //!< its phenotype's hash: what the result applies to
    LoopCheckOutcome outcome = LoopCheckOutcome::Failed;
    double worst = 0.0;  //!< the verdict's deciding difference (relative), 0 unless compared
    //! The experiment's measure taken statically at +-A in both models (verify_body's scores).
    double fem_score = 0.0, engine_score = 0.0;
    std::string verdict;  //!< the one-line verdict, or why it could not be compared
    //! The continuum laws solved for nonlinear steps, the one judged against first (a second
    //! law is solved only where the first does not agree); empty for linear steps.
    std::vector<std::string> laws;
    bool compared() const {
        return outcome == LoopCheckOutcome::Agrees || outcome == LoopCheckOutcome::Differs;
    }
    bool operator==(const LoopCheck&) const = default;
};

//! What one body's check needs. The body is the framed phenotype body (what is simulated).
struct LoopCheckRequest {
    std::int64_t id = 0;
    std::uint64_t hash = 0;
    Body body;
    bool operator==(const LoopCheckRequest&) const = default;
};

//! Bodies picked for checking whose results have not landed yet: kept in the checkpoint, so a
//! run resumed before they land starts the same checks again.
struct PendingChecks {
    int generation = 0;  //!< picked from this generation's population
    std::vector<LoopCheckRequest> picks;
    bool operator==(const PendingChecks&) const = default;
};

//! The generation whose selection the checks picked from `picked` land in: every_generations
//! later (at least one), so they run beside that many generations' simulations and land just
//! before the next bodies are picked.
int landing_generation(const LoopVerifySettings& settings, int picked);

//! Checks one body in a continuum model. Called on the check job's thread, one body at a time.
class ContinuumChecker {
  public:
    virtual ~ContinuumChecker() = default;
    //! nullopt when `cancel` was raised (the solve is abandoned, nothing is kept); a failed solve
    //! is a result (LoopCheckOutcome::Failed with its reason), never an exception. out_dir: the
    //! run's directory ("" = keep no files).
    virtual std::optional<LoopCheck> check(const Experiment& rules, const LoopCheckRequest& body,
                                           const std::string& out_dir,
                                           const std::atomic<bool>& cancel) = 0;
    //! "" when checks can run here, else why not (e.g. CalculiX missing), one line.
    virtual std::string unavailable() const { return ""; }
};

//! Whether the bodies of generation g are checked (after every `every_generations`: g = N-1,
//! 2N-1, ...).
bool is_check_generation(const LoopVerifySettings& settings, int generation);

//! The checks applied so far, by phenotype hash (a later check of the same body wins).
using LoopCheckIndex = std::unordered_map<std::uint64_t, const LoopCheck*>;
LoopCheckIndex index_checks(const std::vector<LoopCheck>& checks);

//! The top_k best distinct phenotypes of the population and the champion (valid first, then
//! fitness, then age and id: best_member's order) that no check has seen yet.
std::vector<LoopCheckRequest> pick_for_check(const std::vector<Individual>& population,
                                             const Individual* champion,
                                             const LoopVerifySettings& settings,
                                             const LoopCheckIndex& done);

//! The factor penalise applies: the FEM's static score over ours, at most 1, where the body
//! differs; 1 where it agrees (within the check's tolerance the two answers are not told apart:
//! the ratio there is the FEM's own uncertainty, and depends on which continuum law was solved,
//! docs/verify.md), was not compared, or ours barely moves.
double penalty_factor(const LoopCheck& check);

//! Applies the policy to a member whose result and validity were just set under `rules` (from
//! its measures: calling it again changes nothing). flag: nothing; penalise: a positive fitness
//! times penalty_factor; reject: a body that differs becomes invalid.
void apply_loop_check(Individual& member, const Experiment& rules, const LoopCheckIndex& checks);

//! The checks of one generation's picks, run one after another on a thread of the job's own.
//! Destroying a job that has not been joined cancels it and waits for the thread.
class LoopCheckJob {
  public:
    LoopCheckJob(std::shared_ptr<ContinuumChecker> checker, Experiment rules, int generation,
                 std::vector<LoopCheckRequest> picks, std::string out_dir);
    ~LoopCheckJob();
    LoopCheckJob(const LoopCheckJob&) = delete;
    LoopCheckJob& operator=(const LoopCheckJob&) = delete;
    //! Waits for every check; nullopt when the job was cancelled, by cancel() or by `stop`
    //! being raised while it waits (the run's stop flag: a stop reaches into the solve).
    std::optional<std::vector<LoopCheck>> join(const std::atomic<bool>* stop = nullptr);
    void cancel() { cancel_.store(true); }
    int generation() const { return generation_; }

  private:
    void work();
    std::shared_ptr<ContinuumChecker> checker_;
    Experiment rules_;
    int generation_ = 0;
    std::vector<LoopCheckRequest> picks_;
    std::string out_dir_;
    std::atomic<bool> cancel_{false};
    std::atomic<bool> finished_{false};
    std::vector<LoopCheck> results_;
    bool cancelled_ = false;
    std::thread thread_;
};

//! fitness.csv's columns of a generation with checks in the loop.
struct LoopCheckRow {
    int verified = 0;  //!< checks that landed in this generation
    //! Whether the champion after this generation was checked and agrees (nullopt: not checked
    //! or not compared).
    std::optional<bool> champion_agrees;
    //! The largest deciding difference among this generation's compared checks.
    std::optional<double> worst_difference;
    bool operator==(const LoopCheckRow&) const = default;
};

LoopCheckRow loop_check_row(const std::vector<LoopCheck>& landed, const Individual* champion,
                            const LoopCheckIndex& all);

}  // namespace bhm::evo
