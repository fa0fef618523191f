#include "app/gui/session/evolution_session.hpp"

#include <chrono>
#include <cstdio>
#include <filesystem>
#include <functional>

#include "evo/run/evolution_run.hpp"
#include "evo/run/run_directory.hpp"
#include "evo/verify/continuum_checker.hpp"

namespace bhm::app::gui {

const char* run_phase_name(RunPhase phase) {
    switch (phase) {
        case RunPhase::Idle:
            return "idle";
        case RunPhase::Running:
            return "running";
        case RunPhase::Pausing:
            return "pausing";
        case RunPhase::Paused:
            return "paused";
        case RunPhase::Stopping:
            return "stopping";
        case RunPhase::Finished:
            return "finished";
        case RunPhase::Stopped:
            return "stopped";
        case RunPhase::Failed:
            return "failed";
    }
    return "?";
}

std::string describe_fitness_change(const evo::Fitness& before, const evo::Fitness& after) {
    std::string what;
    auto add = [&](const std::string& s) { what += (what.empty() ? "" : ", ") + s; };
    if (before.measure != after.measure)
        add(std::string("measure ") + evo::kFitnessNames[static_cast<std::size_t>(after.measure)]);
    const auto& b = before.constraints;
    const auto& a = after.constraints;
    if (b.attached_to_fixed_face != a.attached_to_fixed_face)
        add(a.attached_to_fixed_face ? "must touch the fixed faces" : "attachment not required");
    char text[96];
    if (b.min_fill_fraction != a.min_fill_fraction) {
        std::snprintf(text, sizeof text, "min fill %.3g", a.min_fill_fraction);
        add(text);
    }
    if (b.min_active_voxels != a.min_active_voxels)
        add("min active " + std::to_string(a.min_active_voxels));
    if (before.minimize_active_voxels != after.minimize_active_voxels)
        add(after.minimize_active_voxels ? "minimise active voxels"
                                         : "active voxels not minimised");
    if (before.volume_objective != after.volume_objective)
        add(std::string("volume objective ") +
            evo::kVolumeObjectiveNames[static_cast<std::size_t>(after.volume_objective)]);
    const auto reject = [&](bool b, bool a, const char* flag) {
        if (b != a) add(std::string(a ? "reject " : "allow ") + flag);
    };
    reject(b.reject_escaped, a.reject_escaped, "escaped");
    reject(b.reject_detached_motion, a.reject_detached_motion, "detached motion");
    reject(b.reject_tentacle, a.reject_tentacle, "tentacle");
    return what.empty() ? "rules re-applied" : what;
}

std::string describe_verify_settings(const evo::LoopVerifySettings& v) {
    if (!v.enabled()) return "CalculiX checks off";
    char text[160];
    std::snprintf(text, sizeof text,
                  "CalculiX checks every %d generation%s, top %d, policy %s, tolerance %.3g",
                  v.every_generations, v.every_generations == 1 ? "" : "s", v.top_k,
                  evo::kVerifyPolicyNames[static_cast<std::size_t>(v.policy)], v.tolerance);
    return text;
}

namespace {

// The fitness and physics part of describe_rule_change.
std::string describe_rules_part(const evo::Experiment& started, const evo::Fitness& initial,
                                const std::vector<evo::RuleChange>& changes, std::size_t i) {
    const evo::RuleChange& c = changes[i];
    const evo::Fitness& before = i == 0 ? initial : changes[i - 1].fitness;
    if (!c.physics) return describe_fitness_change(before, c.fitness);
    evo::Experiment was = started;
    for (std::size_t j = i; j-- > 0;) {
        if (!changes[j].physics) continue;
        try {
            was = evo::with_physics(started, *changes[j].physics);
        } catch (const std::exception&) {  // read from a file: say what changed against the start
        }
        break;
    }
    const std::string physics = evo::describe_physics_change(was, *c.physics);
    return before == c.fitness ? physics : describe_fitness_change(before, c.fitness) + "; " + physics;
}

}  // namespace

std::string describe_rule_change(const evo::Experiment& started, const evo::Fitness& initial,
                                 const std::vector<evo::RuleChange>& changes, std::size_t i) {
    const evo::RuleChange& c = changes[i];
    if (!c.verify) return describe_rules_part(started, initial, changes, i);
    // A change of the continuum checks alone leaves the fitness as it was: say only what it set.
    const evo::Fitness& before = i == 0 ? initial : changes[i - 1].fitness;
    const std::string verify = describe_verify_settings(*c.verify);
    if (before == c.fitness && !c.physics) return verify;
    return describe_rules_part(started, initial, changes, i) + "; " + verify;
}

const evo::LoopCheck* loop_check_of(const EvolutionSnapshot& run, std::int64_t id) {
    if (run.loop_checks.empty()) return nullptr;
    const PopulationMember* member = nullptr;
    if (run.has_champion && run.champion.id == id) member = &run.champion;
    for (const auto& m : run.population)
        if (!member && m.id == id) member = &m;
    // The last check wins, as evo::index_checks has it.
    for (auto it = run.loop_checks.rbegin(); it != run.loop_checks.rend(); ++it)
        if (member ? it->hash == member->hash : it->id == id) return &*it;
    return nullptr;
}

// Shared with the run thread. The run thread owns `run`; the UI thread only calls its
// thread-safe controls (request_stop, request_fitness_change) and our own flags below.
struct EvolutionSession::Shared {
    std::unique_ptr<evo::EvolutionRun> run;
    //! The run for progress(): set once the run exists, read by the UI thread.
    std::atomic<evo::EvolutionRun*> live{nullptr};
    std::string resume_dir;  //!< set: the thread resumes this directory first
    std::string run_dir;
    std::mutex mutex;
    bool paused = false;
    bool freeze = false;  //!< the pause froze the simulations in flight (set_paused)
    bool stop = false;
    bool created_dir = false;  //!< start() made the run folder (it did not exist before)
    // Built on the run thread only.
    std::vector<GenerationRecord> history;
    std::vector<RuleChangeNote> changes;
    std::int64_t simulations = 0;
    evo::Fitness initial_fitness;  //!< the rules before the first change (for the markers' text)
};

namespace {

// Turns the run's state after a completed generation into the UI's snapshot. Called on the run
// thread between generations (from run_generation's report callback or our loop), when the state
// is committed and nothing else touches it.
std::shared_ptr<EvolutionSnapshot> snapshot_of(EvolutionSession::Shared& sh, RunPhase phase,
                                               const std::string& message) {
    auto snap = std::make_shared<EvolutionSnapshot>();
    snap->phase = phase;
    snap->message = message;
    snap->run_dir = sh.run_dir;
    if (!sh.run) return snap;
    snap->loaded = true;
    snap->initial_measure = sh.initial_fitness.measure;
    const evo::EvolutionRun& run = *sh.run;
    const evo::RunState& state = run.state();
    snap->experiment = state.experiment;
    snap->generation = state.generation + 1;
    snap->generation_budget = run.generation_budget();
    snap->elapsed_s = state.elapsed_s;
    // History rows we have not converted yet (all of them after a resume).
    for (std::size_t i = sh.history.size(); i < state.history.size(); ++i) {
        const auto& row = state.history[i];
        sh.simulations += row.simulations;
        sh.history.push_back(
            {row.generation, row.best_fitness, row.median_fitness, row.wall_s, sh.simulations});
    }
    for (std::size_t i = sh.changes.size(); i < state.rule_changes.size(); ++i)
        sh.changes.push_back({state.rule_changes[i].generation,
                              describe_rule_change(run.started_experiment(), sh.initial_fitness,
                                                   state.rule_changes, i),
                              state.rule_changes[i].fitness.measure});
    snap->history = sh.history;
    snap->rule_changes = sh.changes;
    snap->species = state.history.empty() ? 0 : state.history.back().species;
    snap->novelty = state.history.empty() ? std::nullopt : state.history.back().novelty;
    snap->evaluations = sh.simulations;
    if (const auto report = run.latest_report()) {
        snap->simulations_per_s = report->simulations_per_s;
        snap->eta_s = report->eta_s;
    }
    snap->loop_checks = state.loop_checks;
    const evo::LoopCheckIndex checks = evo::index_checks(snap->loop_checks);
    // The badge's figures (evo's summary_of leaves them to the generation report).
    const auto with_check = [&](PopulationMember& p, const evo::Individual& m) {
        p.hash = m.phenotype.hash;
        if (const auto it = checks.find(p.hash); it != checks.end()) {
            p.check = it->second->outcome;
            p.check_worst = it->second->worst;
        }
    };
    const auto species_of = evo::species_of_members(state.neat, state.population.size());
    for (std::size_t k = 0; k < state.population.size(); ++k) {
        const auto& m = state.population[k];
        PopulationMember p;
        static_cast<evo::MemberSummary&>(p) = evo::summary_of(m);
        if (species_of[k] >= 0)
            p.species = state.neat.species[static_cast<std::size_t>(species_of[k])].id;
        p.pareto_rank = k < state.pareto_rank.size() ? state.pareto_rank[k] : 0;
        p.novelty = k < state.novelty.size() ? state.novelty[k] : -1.0;
        p.body = std::make_shared<const evo::Body>(m.phenotype.body);
        with_check(p, m);
        snap->population.push_back(std::move(p));
    }
    std::stable_sort(
        snap->population.begin(), snap->population.end(),
        [](const PopulationMember& a, const PopulationMember& b) { return a.fitness > b.fitness; });
    if (state.champion) {
        const auto& c = state.champion->individual;
        snap->has_champion = true;
        snap->champion_generation = state.champion->generation_found;
        snap->best_fitness = c.report.fitness;
        PopulationMember& p = snap->champion;
        static_cast<evo::MemberSummary&>(p) = evo::summary_of(c);
        with_check(p, c);
        // The population's copy when the champion is in it, so the pointer is shared.
        for (const auto& m : snap->population)
            if (m.id == c.id) p.body = m.body;
        if (!p.body) p.body = std::make_shared<const evo::Body>(c.phenotype.body);
    }
    return snap;
}

}  // namespace

EvolutionSession::EvolutionSession() {
    auto idle = std::make_shared<EvolutionSnapshot>();
    slot_.publish(idle);
}

EvolutionSession::~EvolutionSession() {
    stop();
    if (thread_.joinable()) thread_.join();
    discard_unstarted_folder();
}

void EvolutionSession::join_finished() {
    if (run_is_live(phase_.load()))
        throw std::runtime_error("a run is already going: stop it first");
    if (thread_.joinable()) thread_.join();
    discard_unstarted_folder();
}

void EvolutionSession::collect_ended() {
    const RunPhase phase = phase_.load();
    if (run_is_live(phase) || phase == RunPhase::Idle || !thread_.joinable()) return;
    thread_.join();
    discard_unstarted_folder();
}

void EvolutionSession::discard_unstarted_folder() {
    if (!shared_ || !shared_->created_dir || phase_.load() != RunPhase::Stopped) return;
    if (shared_->run && shared_->run->state().generation >= 0) return;  // it has a checkpoint
    shared_->created_dir = false;
    // The run thread is joined: nobody else reads the run. Dropping it releases the folder's lock.
    shared_->live = nullptr;
    shared_->run.reset();
    namespace fs = std::filesystem;
    const fs::path dir = shared_->run_dir;
    std::error_code ec;
    // Only what the run wrote before its first generation; anything else keeps the folder.
    fs::remove(dir / evo::kRunInfoFile, ec);
    fs::remove(dir / "champions", ec);  // fails, harmlessly, unless empty
    fs::remove(dir, ec);
}

void EvolutionSession::start(const evo::Experiment& experiment, const std::string& run_dir) {
    join_finished();
    evo::RunOptions options;
    options.out_dir = run_dir;
    options.checker = std::make_shared<evo::CalculixChecker>();  // evolution.verify
    // Built here so a bad folder (one holding a checkpoint, unwritable) is reported at once; the
    // constructor only creates the folder and writes run.json. Handing the built run to the
    // thread also makes the very first snapshot complete (rules, budget), so the Run panel is
    // right from the frame after Start.
    std::error_code ec;
    const bool existed = std::filesystem::exists(run_dir, ec);
    launch(std::make_unique<evo::EvolutionRun>(experiment, options), {}, run_dir,
           "generation 0: creating the population");
    shared_->created_dir = !existed;
}

void EvolutionSession::resume_from(const std::string& run_dir) {
    join_finished();
    // Loading a checkpoint parses megabytes of JSON: done on the run thread, not the UI's; the
    // snapshot says so (loaded = false) until it is in.
    launch(
        nullptr,
        [run_dir] {
            evo::RunOptions options;
            options.out_dir = run_dir;
            options.checker = std::make_shared<evo::CalculixChecker>();
            return evo::EvolutionRun::resume(options);
        },
        run_dir, "resuming: loading the checkpoint");
}

void EvolutionSession::launch(std::unique_ptr<evo::EvolutionRun> ready,
                              std::function<std::unique_ptr<evo::EvolutionRun>()> make,
                              const std::string& run_dir, const std::string& first_message) {
    auto shared = std::make_shared<Shared>();
    shared->run_dir = run_dir;
    if (ready) {
        const auto& state = ready->state();
        shared->initial_fitness = state.rule_changes.empty() ? state.experiment.fitness
                                                             : state.rule_changes.front().fitness;
        shared->run = std::move(ready);
        shared->live = shared->run.get();
    }
    shared_ = shared;
    sent_rules_.reset();
    sent_verify_.reset();
    phase_ = RunPhase::Running;
    slot_.publish(snapshot_of(*shared, RunPhase::Running, first_message));
    thread_ = std::thread([this, shared, make = std::move(make)] {
        auto publish = [&](RunPhase phase, const std::string& message) {
            phase_ = phase;
            slot_.publish(snapshot_of(*shared, phase, message));
        };
        try {
            if (!shared->run) {
                auto made = make();
                std::lock_guard lock(shared->mutex);
                const auto& state = made->state();
                shared->initial_fitness = state.rule_changes.empty()
                                              ? state.experiment.fitness
                                              : state.rule_changes.front().fitness;
                shared->run = std::move(made);
                shared->live = shared->run.get();
                // A stop or pause asked for while the checkpoint loaded reaches the run now.
                if (shared->stop) shared->run->request_stop();
                if (shared->paused && shared->freeze) shared->run->set_paused(true);
                if (shared->paused && !shared->freeze) shared->run->pause_between_generations(true);
            }
            evo::EvolutionRun& run = *shared->run;
            // Shown at once (the history, the rules, the budget): nothing waits for a generation.
            publish(RunPhase::Running,
                    run.resume_warnings().empty()
                        ? (run.state().generation >= 0
                               ? "resumed from the checkpoint of generation " +
                                     std::to_string(run.state().generation)
                               : std::string("generation 0: creating the population"))
                        : run.resume_warnings().front());
            run.set_report_callback([&](std::shared_ptr<const evo::GenerationReport> report) {
                char text[160];
                std::snprintf(text, sizeof text,
                              "generation %d done: %d simulations, %d from the cache%s",
                              report->generation, report->simulations, report->cache_hits,
                              report->new_champion ? ", new champion" : "");
                std::lock_guard lock(shared->mutex);
                const RunPhase now = shared->stop ? RunPhase::Stopping
                                     : shared->paused
                                         ? (shared->freeze ? RunPhase::Paused : RunPhase::Pausing)
                                         : RunPhase::Running;
                phase_ = now;
                slot_.publish(snapshot_of(*shared, now, text));
            });
            // The run's own loop drives the studio: its events say when it holds between
            // generations and when it goes on. A pause freezes the simulations in flight
            // (set_paused) or lets the generation finish first (pause_between_generations). A
            // change of rules abandons the generation in progress, which the run computes again
            // from the same random state, so the run stays identical to an uninterrupted one.
            run.set_event_callback([&](evo::RunEvent event, int next, bool restarted) {
                if (event == evo::RunEvent::Paused) {
                    publish(RunPhase::Paused, restarted ? "paused: generation " +
                                                              std::to_string(next) +
                                                              " is computed again on resume"
                                                        : std::string("paused between generations"));
                } else if (event == evo::RunEvent::Resumed) {
                    publish(RunPhase::Running, "resumed");
                }
            });
            switch (run.run()) {
                case evo::StopReason::GenerationBudget:
                    publish(RunPhase::Finished, "finished: generation budget reached");
                    return;
                case evo::StopReason::WallBudget:
                    publish(RunPhase::Finished, "finished: wall-time budget reached");
                    return;
                case evo::StopReason::StopRequested: break;
            }
            const int done = run.state().generation;
            // The abandoned generation's time stays on the clock, in the checkpoint too: a
            // resumed run's elapsed time goes on from here instead of going back.
            run.keep_stopped_time();
            auto stopped = snapshot_of(
                *shared, RunPhase::Stopped,
                done >= 0 ? "stopped: the checkpoint of generation " + std::to_string(done) +
                                " is kept; resume it from " + shared->run_dir
                          : std::string("stopped during generation 0: no generation was "
                                        "completed, so there is no checkpoint to resume "
                                        "(its empty folder is removed)"));
            stopped->stopped_time_kept = true;
            phase_ = RunPhase::Stopped;
            slot_.publish(std::move(stopped));
        } catch (const std::exception& e) {
            publish(RunPhase::Failed, std::string("run failed: ") + e.what());
        }
    });
}

void EvolutionSession::pause(bool between_generations) {
    if (!shared_) return;
    std::lock_guard lock(shared_->mutex);
    if (between_generations) {
        // Unfreeze (a pause of the other kind may hold the simulations) and stop after this one.
        shared_->paused = true;
        shared_->freeze = false;
        if (shared_->run) {
            shared_->run->set_paused(false);
            shared_->run->pause_between_generations(true);
        }
        if (phase_ == RunPhase::Running || phase_ == RunPhase::Paused) phase_ = RunPhase::Pausing;
        return;
    }
    shared_->paused = true;
    shared_->freeze = true;
    // The simulations in flight stop stepping within milliseconds: the run is paused now.
    if (shared_->run) shared_->run->set_paused(true);
    if (phase_ == RunPhase::Running || phase_ == RunPhase::Pausing) phase_ = RunPhase::Paused;
}

LiveProgress EvolutionSession::progress() const {
    LiveProgress out;
    if (!shared_) return out;
    const evo::EvolutionRun* run = shared_->live.load();
    if (!run) return out;
    const auto p = run->progress();
    out.running = p.running;
    out.generation = p.generation;
    out.simulations_done = p.simulations_done;
    out.simulations_total = p.simulations_total;
    out.generation_s = p.elapsed_s;
    out.abandoned_s = p.abandoned_s;
    return out;
}

LiveFigures live_figures(const EvolutionSnapshot& run, const LiveProgress& p, RunPhase phase) {
    LiveFigures f;
    f.elapsed_s = run.elapsed_s;
    f.simulations = run.evaluations;
    f.simulations_per_s = run.simulations_per_s;
    const bool running = phase == RunPhase::Running;
    f.eta_s = running ? run.eta_s : -1.0;
    if (p.generation < run.generation) return f;  // no generation after the snapshot's yet
    if (run.stopped_time_kept) return f;          // the stopped generation's time is in it
    // The next generation's time so far, its attempts abandoned for new rules included, also
    // once an attempt has ended: without them the clock would jump back when one is abandoned.
    f.elapsed_s += p.abandoned_s + p.generation_s;
    if (!p.running) return f;
    f.simulations += p.simulations_done;
    if (p.simulations_done > 0 && p.generation_s > 0.0)
        f.simulations_per_s = p.simulations_done / p.generation_s;
    // Remaining: the rest of this generation at its own rate, then the remaining generations at
    // the mean time of the completed ones (or this one's projected time when none is complete).
    const double rate = f.simulations_per_s;
    const double this_left =
        rate > 0.0 ? std::max(0, p.simulations_total - p.simulations_done) / rate : -1.0;
    const double mean_generation_s = run.generation > 0
                                         ? run.elapsed_s / run.generation
                                         : (this_left >= 0.0 ? p.generation_s + this_left : -1.0);
    const int after = run.generation_budget - p.generation - 1;
    if (running && this_left >= 0.0 && mean_generation_s >= 0.0)
        f.eta_s = this_left + std::max(0, after) * mean_generation_s;
    return f;
}

void EvolutionSession::resume() {
    if (!shared_) return;
    {
        std::lock_guard lock(shared_->mutex);
        const bool frozen = shared_->freeze;
        shared_->paused = false;
        shared_->freeze = false;
        if (shared_->run) shared_->run->set_paused(false);
        // Frozen inside a generation: it goes on at once (the loop is not waiting).
        if (phase_ == RunPhase::Pausing || (frozen && phase_ == RunPhase::Paused))
            phase_ = RunPhase::Running;
    }
}

void EvolutionSession::stop() {
    if (!shared_ || !run_is_live(phase_.load())) return;
    {
        std::lock_guard lock(shared_->mutex);
        shared_->stop = true;
        phase_ = RunPhase::Stopping;
        if (shared_->run) {
            shared_->run->request_stop();  // thread-safe: aborts the simulations in flight
            shared_->run->set_paused(false);
        }
    }
}

void EvolutionSession::change_physics(const evo::PhysicsRules& physics) {
    if (!shared_ || !run_is_live(phase_.load())) throw std::runtime_error("no live run");
    std::lock_guard lock(shared_->mutex);
    if (!shared_->run) throw std::runtime_error("the run is still loading its checkpoint");
    // As change_rules: a generation in progress is abandoned and computed again under the new
    // physics. Throws std::invalid_argument for physics the run cannot take.
    if (shared_->stop)
        shared_->run->request_physics_change(physics);
    else
        shared_->run->change_physics_now(physics);
}

void EvolutionSession::change_verify(const evo::LoopVerifySettings& settings) {
    if (!shared_ || !run_is_live(phase_.load())) throw std::runtime_error("no live run");
    std::lock_guard lock(shared_->mutex);
    if (!shared_->run) throw std::runtime_error("the run is still loading its checkpoint");
    // Not restarting the generation in flight: the checks and the policy act between
    // generations (the checks of this one start with the next), so the change waits for it.
    shared_->run->request_verify_change(settings);
    sent_verify_ = settings;
}

void EvolutionSession::change_rules(const evo::Experiment& experiment) {
    if (!shared_ || !run_is_live(phase_.load())) return;
    std::lock_guard lock(shared_->mutex);
    if (!shared_->run) return;
    sent_rules_ = experiment;
    // A generation in progress (or frozen by a pause) would finish under the old rules: the run
    // abandons it and computes it again under the new ones (thread-safe).
    if (shared_->stop)
        shared_->run->request_fitness_change(experiment.fitness);
    else
        shared_->run->change_fitness_now(experiment.fitness);
}

std::string exploit_summary(const evo::ExploitReport& r) {
    if (!r.checked || !r.any()) return "";
    std::string out;
    char text[96];
    auto add = [&](const char* t) { out += (out.empty() ? "" : ", ") + std::string(t); };
    if (r.escaped) {
        std::snprintf(text, sizeof text, "escaped (%.0f %% of the voxels unanchored)",
                      100.0 * r.unanchored_fraction);
        add(text);
    }
    if (r.detached_motion) {
        std::snprintf(text, sizeof text, "detached motion (base motion ratio %.2f)",
                      r.base_motion_ratio);
        add(text);
    }
    if (r.tentacle) {
        std::snprintf(text, sizeof text, "tentacle (thin voxels carry %.0f %% of the motion)",
                      100.0 * r.thin_share);
        add(text);
    }
    return out;
}

std::string exploit_letters(const evo::ExploitReport& r) {
    if (!r.checked) return "";
    std::string out;
    if (r.escaped) out += "E";
    if (r.detached_motion) out += "D";
    if (r.tentacle) out += "T";
    return out;
}

}  // namespace bhm::app::gui
