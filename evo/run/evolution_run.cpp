#include "evo/run/evolution_run.hpp"

#include <algorithm>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <stdexcept>
#include <unordered_map>

#include "evo/evaluate/constraints.hpp"
#include "evo/evaluate/worker_pool.hpp"
#include "evo/experiment/experiment_io.hpp"
#include "evo/run/cached_evaluation.hpp"
#include "evo/run/checkpoint.hpp"
#include "evo/run/run_directory.hpp"
#include "evo/run/run_lock.hpp"
#include "evo/search/search_algorithm.hpp"

namespace bhm::evo {

namespace fs = std::filesystem;

namespace {

double seconds_since(std::chrono::steady_clock::time_point start) {
    return std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
}

//! Creates DIR if needed and takes its lock: before anything in it is read or written.
std::shared_ptr<RunDirectoryLock> lock_run_directory(const RunOptions& options, bool create) {
    if (options.out_dir.empty()) return nullptr;
    std::error_code ec;
    if (create) fs::create_directories(options.out_dir, ec);
    if (!fs::is_directory(options.out_dir, ec))
        throw std::runtime_error(options.out_dir + (create ? ": cannot create the run directory"
                                                           : ": no such run directory"));
    return std::make_shared<RunDirectoryLock>(options.out_dir, options.writer);
}

}  // namespace

EvolutionRun::Start EvolutionRun::fresh_start(const Experiment& experiment,
                                              const RunOptions& options) {
    Start s;
    s.original = experiment;
    if (options.seed) s.original.evolution.seed = *options.seed;
    s.state.experiment = s.original;
    s.state.seed = s.original.evolution.seed;
    s.state.rng = Rng(s.state.seed).state();
    s.lock = lock_run_directory(options, true);
    if (!options.out_dir.empty()) {
        for (const char* name : {kCheckpointFile, kPreviousCheckpointFile})
            if (fs::exists(fs::path(options.out_dir) / name))
                throw std::runtime_error(options.out_dir + ": already holds a run (" + name +
                                         "); continue it with --resume or choose another --out");
    }
    return s;
}

EvolutionRun::EvolutionRun(const Experiment& experiment, RunOptions options)
    : EvolutionRun(fresh_start(experiment, options), options) {
}  // a copy: argument order is unspecified

std::unique_ptr<EvolutionRun> EvolutionRun::resume(RunOptions options) {
    if (options.out_dir.empty()) throw std::invalid_argument("resuming needs the run directory");
    auto lock = lock_run_directory(options, false);
    auto loaded = load_checkpoint(options.out_dir);
    if (options.seed && *options.seed != loaded.state.seed)
        throw std::invalid_argument("--seed " + std::to_string(*options.seed) +
                                    " differs from the run's seed " +
                                    std::to_string(loaded.state.seed));
    Start s;
    s.state = std::move(loaded.state);
    s.warnings = std::move(loaded.warnings);
    s.checkpoint_path = loaded.path;
    s.resumed = true;
    s.lock = std::move(lock);
    try {
        RunInfo info = read_run_info(options.out_dir);
        s.original = std::move(info.started);
        // run.json disagreed with the checkpoint: the checkpoint is the record; run.json is
        // rewritten from it, and the run says so.
        for (auto& w : info.warnings)
            s.warnings.push_back(std::move(w) + "; run.json rewritten from it");
        s.rewrite_run_info = !info.warnings.empty();
    } catch (const std::exception& e) {
        s.warnings.push_back(std::string(e.what()) +
                             "; rewritten from the checkpoint's experiment (its current rules)");
        s.original = s.state.experiment;
        s.rewrite_run_info = true;
    }
    return std::unique_ptr<EvolutionRun>(new EvolutionRun(std::move(s), std::move(options)));
}

EvolutionRun::EvolutionRun(Start start, RunOptions options)
    : options_(std::move(options)),
      lock_(std::move(start.lock)),
      original_experiment_(std::move(start.original)),
      state_(std::move(start.state)),
      developer_(state_.experiment),
      resume_warnings_(std::move(start.warnings)),
      checkpoint_path_(std::move(start.checkpoint_path)) {
    const auto& evolution = state_.experiment.evolution;
    generation_budget_ = options_.generations.value_or(evolution.generations);
    wall_budget_s_ = options_.wall_budget_h.value_or(evolution.wall_budget_h) * 3600.0;
    threads_ = resolve_thread_count(options_.threads.value_or(evolution.threads));
    evaluator_ =
        options_.evaluator ? options_.evaluator : std::make_shared<ThreadEvaluator>(threads_);
    checker_ = options_.checker;
    require_checker(evolution.verify);
    if (generation_budget_ < 0) throw std::invalid_argument("the generation budget must be >= 0");
    if (!(wall_budget_s_ > 0.0))
        throw std::invalid_argument("the wall-time budget must be > 0 hours");
    if (evolution.population < 1) throw std::invalid_argument("evolution.population must be >= 1");
    if (!options_.out_dir.empty()) {
        output_.emplace(options_.out_dir);
        if (!start.resumed || start.rewrite_run_info)
            output_->write_run_info(original_experiment_, state_);
    }
}

EvolutionRun::~EvolutionRun() = default;

void EvolutionRun::pause_between_generations(bool hold) {
    {
        std::lock_guard lock(control_mutex_);
        hold_.store(hold);
    }
    control_changed_.notify_all();
}

void EvolutionRun::set_paused(bool paused) {
    {
        if (!paused) hold_.store(false);
        std::lock_guard lock(control_mutex_);
        const auto now = std::chrono::steady_clock::now();
        if (paused && !paused_.load()) pause_began_ = now;
        if (!paused && paused_.load())
            paused_s_ += std::chrono::duration<double>(now - pause_began_).count();
        paused_.store(paused);
    }
    control_changed_.notify_all();
}

double EvolutionRun::paused_seconds() const {
    return paused_seconds_now().first;
}

std::pair<double, std::chrono::steady_clock::time_point> EvolutionRun::paused_seconds_now() const {
    std::lock_guard lock(control_mutex_);
    const auto now = std::chrono::steady_clock::now();
    double s = paused_s_;
    if (paused_.load()) s += std::chrono::duration<double>(now - pause_began_).count();
    return {s, now};
}

GenerationProgress EvolutionRun::progress() const {
    GenerationProgress p;
    double paused_at_start = 0.0;
    std::chrono::steady_clock::time_point start;
    {
        std::lock_guard lock(progress_mutex_);
        p = progress_;
        paused_at_start = progress_paused_at_start_s_;
        start = progress_start_;
    }
    if (p.running) {
        // One instant for both readings: apart, a reader preempted between them (a loaded
        // machine) saw the time in a paused generation jitter, even go back.
        const auto [paused, now] = paused_seconds_now();
        p.elapsed_s = std::max(0.0, std::chrono::duration<double>(now - start).count() -
                                        (paused - paused_at_start));
    }
    return p;
}

void EvolutionRun::progress_begin(int generation) {
    const double paused = paused_seconds();
    std::lock_guard lock(progress_mutex_);
    // Another attempt at the same generation keeps the time of the abandoned ones (unless a
    // stop already put it into the run's elapsed time).
    const double abandoned = progress_.generation == generation && !abandoned_time_kept_
                                 ? progress_.abandoned_s
                                 : 0.0;
    abandoned_time_kept_ = false;
    progress_ = GenerationProgress{true, generation, 0, 0, 0.0, abandoned};
    progress_start_ = std::chrono::steady_clock::now();
    progress_paused_at_start_s_ = paused;
}

void EvolutionRun::progress_set_total(int simulations) {
    std::lock_guard lock(progress_mutex_);
    progress_.simulations_total = simulations;
}

void EvolutionRun::progress_count_one() {
    std::lock_guard lock(progress_mutex_);
    ++progress_.simulations_done;
}

void EvolutionRun::progress_end() {
    const GenerationProgress last = progress();
    std::lock_guard lock(progress_mutex_);
    progress_.running = false;
    progress_.elapsed_s = last.elapsed_s;
}

void EvolutionRun::progress_abandoned() {
    std::lock_guard lock(progress_mutex_);
    progress_.abandoned_s += progress_.elapsed_s;
    progress_.elapsed_s = 0.0;
}

void EvolutionRun::keep_stopped_time() {
    double spent = 0.0;
    {
        std::lock_guard lock(progress_mutex_);
        if (abandoned_time_kept_ || progress_.generation != state_.generation + 1) return;
        spent = progress_.abandoned_s;
        abandoned_time_kept_ = true;
    }
    if (!(spent > 0.0)) return;
    state_.elapsed_s += spent;
    if (output_ && state_.generation >= 0) {
        const bool resumed_from_backup =
            fs::path(checkpoint_path_).filename() == kPreviousCheckpointFile;
        output_->write_checkpoint(state_, resumed_from_backup);
        checkpoint_path_ = output_->path(kCheckpointFile);
    }
}

void EvolutionRun::request_fitness_change(const Fitness& fitness) {
    std::lock_guard lock(control_mutex_);
    pending_fitness_ = fitness;
    ++pending_serial_;
}

void EvolutionRun::change_fitness_now(const Fitness& fitness) {
    request_fitness_change(fitness);
    restart_.store(true);
    stop_.store(true);  // abandons the simulations in flight within milliseconds
}

void EvolutionRun::request_physics_change(const PhysicsRules& physics) {
    // Checked against the experiment the run started with: materials, the active ones and
    // everything but the physics are the same in every generation's rules.
    (void)with_physics(original_experiment_, physics);
    std::lock_guard lock(control_mutex_);
    pending_physics_ = physics;
    ++pending_serial_;
}

void EvolutionRun::require_checker(const LoopVerifySettings& settings) const {
    if (!settings.enabled()) return;
    if (!checker_)
        throw std::invalid_argument(
            "evolution.verify: checks in the loop need a continuum checker, and this front end "
            "has none; set evolution.verify.every_generations to 0");
    if (const std::string why = checker_->unavailable(); !why.empty())
        throw std::invalid_argument("evolution.verify: " + why);
}

void EvolutionRun::request_verify_change(const LoopVerifySettings& settings) {
    if (settings.every_generations < 0)
        throw std::invalid_argument("evolution.verify.every_generations: must be >= 0");
    if (settings.top_k < 1) throw std::invalid_argument("evolution.verify.top_k: must be >= 1");
    if (!(settings.tolerance > 0.0))
        throw std::invalid_argument("evolution.verify.tolerance: must be above 0");
    require_checker(settings);
    std::lock_guard lock(control_mutex_);
    pending_verify_ = settings;
    ++pending_serial_;
}

void EvolutionRun::change_physics_now(const PhysicsRules& physics) {
    request_physics_change(physics);
    restart_.store(true);
    stop_.store(true);
}

std::shared_ptr<const GenerationReport> EvolutionRun::latest_report() const {
    std::lock_guard lock(report_mutex_);
    return latest_;
}

void EvolutionRun::publish(std::shared_ptr<const GenerationReport> report) {
    {
        std::lock_guard lock(report_mutex_);
        latest_ = report;
    }
    if (callback_) callback_(std::move(report));
}

StopReason EvolutionRun::run() {
    if (session_generations_ == 0) session_start_ = std::chrono::steady_clock::now();
    auto tell = [&](RunEvent event, bool restarted) {
        if (events_) events_(event, state_.generation + 1, restarted);
    };
    bool restarted = false;
    for (;;) {
        // A restart asked for after the generation had ended has nothing left to abandon.
        if (restart_.exchange(false) && !user_stop_.load()) stop_.store(false);
        const bool holding = paused_.load() || hold_.load();
        if (holding && !stop_.load()) {
            tell(RunEvent::Paused, restarted);
            {
                // A signal handler cannot notify, so poll the flags while paused. New rules that
                // arrive now abandon nothing: the stop they raised is lowered, the pause goes on.
                std::unique_lock lock(control_mutex_);
                for (;;) {
                    if (restart_.exchange(false) && !user_stop_.load()) stop_.store(false);
                    if (!(paused_.load() || hold_.load()) || stop_.load()) break;
                    control_changed_.wait_for(lock, std::chrono::milliseconds(100));
                }
            }
            if (!stop_.load()) tell(RunEvent::Resumed, false);
        }
        if (stop_.load()) return StopReason::StopRequested;
        if (state_.generation + 1 >= generation_budget_) return StopReason::GenerationBudget;
        if (state_.elapsed_s >= wall_budget_s_) return StopReason::WallBudget;
        restarted = false;
        if (run_generation()) continue;
        // Abandoned: for new rules (computed again at once) or a stop.
        progress_abandoned();
        if (!restart_.exchange(false) || user_stop_.load()) return StopReason::StopRequested;
        stop_.store(false);
        restarted = true;
        tell(RunEvent::Restarted, false);
    }
}

bool EvolutionRun::run_generation() {
    const auto start = std::chrono::steady_clock::now();
    if (session_generations_ == 0) session_start_ = start;
    const int g = state_.generation + 1;
    progress_begin(g);
    struct ProgressEnd {  // on every way out, exceptions included
        EvolutionRun& run;
        ~ProgressEnd() { run.progress_end(); }
    } progress_end_guard{*this};

    // Everything below works on copies; state_ changes only once the generation is complete, so
    // an abandoned generation leaves the last checkpoint's state intact.
    std::uint64_t applied_serial = 0;
    Rescored rescored = rescore_for_pending_rules(applied_serial);
    const Experiment& rules = rescored.rules;
    const auto algorithm = make_search_algorithm(rules.evolution);
    const GenerationContext context{rules, developer_, g};
    SearchState search{state_.neat, state_.novelty_archive};

    EvaluationBatch controls;
    controls.cancel = &stop_;
    controls.pause = &paused_;
    controls.on_result = [this](std::size_t) { progress_count_one(); };
    // New physics: every member is simulated again before anything compares fitnesses, and
    // the cache (keyed by phenotype alone) is replaced by these results.
    CachedEvaluation reevaluation;
    std::optional<FitnessCache> physics_cache;
    if (rescored.physics_changed) {
        for (auto& m : rescored.population)
            m.evaluated = false;
        const FitnessCache none(0);
        try {
            reevaluation = evaluate_fresh(rescored.population, rules, none, *evaluator_, controls,
                                          [this](int total) { progress_set_total(total); });
        } catch (const EvaluationCancelled&) {
            return false;
        }
        const LoopCheckIndex checks = index_checks(state_.loop_checks);
        for (auto& m : rescored.population)
            rescore_member(m, rules, checks);
        physics_cache.emplace(state_.cache.capacity());
        for (std::size_t j = 0; j < reevaluation.simulated_hashes.size(); ++j)
            physics_cache->insert(reevaluation.simulated_hashes[j],
                                  reevaluation.simulated_reports[j]);
    }
    if (rescored.changed) algorithm->rules_changed(context, rescored.population, search);

    // The continuum checks (evo/run/loop_check.hpp): picked from the last generation's best at
    // the beginning of this one, they run beside the simulations of every_generations
    // generations and land before a selection. New rules drop checks made for the old ones.
    std::optional<PendingChecks> pending = state_.pending_checks;
    if (rescored.changed && (pending || check_job_)) {
        check_job_.reset();
        pending.reset();
    }
    if (!pending && checker_ && is_check_generation(rules.evolution.verify, g - 1)) {
        auto picks = pick_for_check(
            rescored.population, rescored.champion ? &rescored.champion->individual : nullptr,
            rules.evolution.verify, index_checks(state_.loop_checks));
        if (!picks.empty()) pending = PendingChecks{g - 1, std::move(picks)};
    }
    if (pending && !check_job_ && checker_)
        check_job_ = std::make_unique<LoopCheckJob>(checker_, rules, pending->generation,
                                                    pending->picks, options_.out_dir);
    const bool checks_land =
        pending && check_job_ && g >= landing_generation(rules.evolution.verify, pending->generation);

    Rng rng;
    rng.set_state(state_.rng);
    std::int64_t next_id = state_.next_id;
    Brood brood = algorithm->breed(context, std::move(rescored.population), search, rng, next_id);

    CachedEvaluation evaluation;
    const int reevaluated = reevaluation.simulations();
    try {
        evaluation = evaluate_fresh(
            brood.fresh, rules, physics_cache ? *physics_cache : state_.cache, *evaluator_,
            controls, [this, reevaluated](int total) { progress_set_total(reevaluated + total); });
    } catch (const EvaluationCancelled&) {
        return false;
    }

    const int evaluations = static_cast<int>(brood.fresh.size());
    std::vector<Individual> pool = std::move(brood.carried);
    const std::size_t first_new = pool.size();
    for (auto& f : brood.fresh)
        pool.push_back(std::move(f));

    // The checks land before selection, and every member (the new ones, cache hits of a checked
    // body, the champion) is judged under the policy with all checks made so far.
    std::vector<LoopCheck> landed;
    if (checks_land) {
        auto results = check_job_->join(&stop_);
        if (!results) {  // stopped: the next attempt at this generation starts them again
            check_job_.reset();
            return false;
        }
        landed = std::move(*results);
        check_job_.reset();
        pending.reset();
    }
    std::optional<ChampionRecord> champion = rescored.champion;
    if (rules.evolution.verify.enabled() || !state_.loop_checks.empty()) {
        std::vector<LoopCheck> all = state_.loop_checks;
        all.insert(all.end(), landed.begin(), landed.end());
        const LoopCheckIndex checks = index_checks(all);
        for (auto& m : pool)
            apply_loop_check(m, rules, checks);
        if (champion) {
            apply_loop_check(champion->individual, rules, checks);
            if (!champion->individual.valid) champion.reset();  // rejected: never champion
        }
    }
    std::optional<Individual> pool_best;
    if (algorithm->champion_from_pool()) pool_best = best_member(pool);
    Selection selection = algorithm->select(context, std::move(pool), first_new, search);

    const Individual& contender = pool_best ? *pool_best : best_member(selection.population);
    const bool new_champion =
        !champion ||
        (contender.valid && contender.report.fitness > champion->individual.report.fitness);
    if (new_champion) champion = ChampionRecord{contender, g};

    GenerationTally tally;
    tally.generation = g;
    tally.rules_version = rescored.rules_version;
    tally.evaluations = evaluations;
    tally.evaluation = &evaluation;
    if (rescored.physics_changed) tally.reevaluation = &reevaluation;
    tally.clones = brood.clones;
    tally.newcomers_skipped = brood.newcomers_skipped;
    if (checks_land) tally.checks_landed = &landed;
    if (pending) tally.pending_checks = &*pending;
    tally.verify_changed = rescored.verify_changed;
    // The generation's clock stops here, before its files are written: it kept running in
    // progress() while they were, so a live figure ran past the time committed below and went
    // back when the generation's snapshot came.
    progress_end();
    const GenerationProgress spent = progress();
    tally.generation_wall_s = spent.elapsed_s;  // paused time excluded
    tally.wall_s = state_.elapsed_s + spent.abandoned_s + tally.generation_wall_s;
    commit_generation(rules, rescored.changed, applied_serial,
                      physics_cache ? &*physics_cache : nullptr, rescored.physics_changed,
                      next_id, rng, std::move(selection),
                      std::move(search), std::move(*champion), tally, new_champion);
    return true;
}

EvolutionRun::Rescored EvolutionRun::rescore_for_pending_rules(
    std::uint64_t& applied_serial) const {
    Rescored out{state_.experiment, state_.population, state_.champion, state_.rules_version,
                 false};
    {
        std::lock_guard lock(control_mutex_);
        if (pending_fitness_) {
            out.rules.fitness = *pending_fitness_;
            applied_serial = pending_serial_;
            out.changed = true;
        }
        // Physics equal to the run's changes nothing (a studio that sends the same values twice
        // must not make every member be simulated again).
        if (pending_physics_ && *pending_physics_ != physics_of(out.rules)) {
            out.rules = with_physics(out.rules, *pending_physics_);
            applied_serial = pending_serial_;
            out.changed = true;
            out.physics_changed = true;
        }
        if (pending_verify_ && *pending_verify_ != out.rules.evolution.verify) {
            out.rules.evolution.verify = *pending_verify_;
            applied_serial = pending_serial_;
            out.changed = true;
            out.verify_changed = true;
        }
    }
    if (!out.changed) return out;
    ++out.rules_version;
    const LoopCheckIndex checks = index_checks(state_.loop_checks);
    for (auto& m : out.population)
        rescore_member(m, out.rules, checks);
    out.champion.reset();  // re-established from the re-scored population
    return out;
}

void EvolutionRun::rescore_member(Individual& m, const Experiment& rules,
                                  const LoopCheckIndex& checks) const {
    m.valid = constraint_violation(rules.fitness.constraints, rules.boundary, developer_.space(),
                                   m.phenotype)
                  .empty();
    m.report.fitness = m.valid ? fitness_under(m.report, rules.fitness) : kInvalidFitness;
    m.valid = m.valid && !rejected_by_exploit(m.report.exploits, rules.fitness.constraints);
    apply_loop_check(m, rules, checks);
}

void EvolutionRun::commit_generation(const Experiment& rules, bool rules_changed,
                                     std::uint64_t applied_serial,
                                     const FitnessCache* physics_cache, bool physics_changed,
                                     std::int64_t next_id,
                                     const Rng& rng, Selection selection, SearchState search,
                                     ChampionRecord champion, const GenerationTally& tally,
                                     bool new_champion) {
    HistoryRow row = make_history_row(tally, selection, search, champion.individual.report.fitness);
    state_.pending_checks = tally.pending_checks
                                ? std::optional<PendingChecks>(*tally.pending_checks)
                                : std::nullopt;
    if (tally.checks_landed)
        state_.loop_checks.insert(state_.loop_checks.end(), tally.checks_landed->begin(),
                                  tally.checks_landed->end());
    if (rules.evolution.verify.enabled() || tally.checks_landed) {
        static const std::vector<LoopCheck> none;
        row.verify = loop_check_row(tally.checks_landed ? *tally.checks_landed : none,
                                    &champion.individual, index_checks(state_.loop_checks));
    }
    state_.experiment = rules;
    state_.generation = tally.generation;
    state_.next_id = next_id;
    state_.rng = rng.state();
    state_.rules_version = tally.rules_version;
    state_.elapsed_s = tally.wall_s;
    state_.population = selection.population;
    state_.pareto_rank = selection.ranks;
    state_.novelty = selection.novelty;
    state_.champion = std::move(champion);
    state_.neat = std::move(search.neat);
    state_.novelty_archive = std::move(search.novelty_archive);
    state_.history.push_back(row);
    if (rules_changed)
        state_.rule_changes.push_back(
            {tally.generation, rules.fitness,
             physics_changed ? std::optional<PhysicsRules>(physics_of(rules)) : std::nullopt,
             tally.verify_changed ? std::optional<LoopVerifySettings>(rules.evolution.verify)
                                  : std::nullopt});
    if (physics_cache) state_.cache = *physics_cache;  // no result of the old physics is kept
    const CachedEvaluation& evaluation = *tally.evaluation;
    for (std::size_t j = 0; j < evaluation.simulated_hashes.size(); ++j)
        state_.cache.insert(evaluation.simulated_hashes[j], evaluation.simulated_reports[j]);
    {
        std::lock_guard lock(control_mutex_);
        if (rules_changed && pending_serial_ == applied_serial) {
            pending_fitness_.reset();
            pending_physics_.reset();
            pending_verify_.reset();
        }
    }
    ++session_generations_;

    if (output_) {
        output_->write_fitness_csv(state_.history);
        output_->write_population_csv(state_);
        if (new_champion) output_->write_champion(rules, *state_.champion);
        // Resumed from the backup (checkpoint.json was damaged): the backup is the one good
        // checkpoint left, so the damaged file goes aside instead of into its slot.
        const bool resumed_from_backup =
            fs::path(checkpoint_path_).filename() == kPreviousCheckpointFile;
        output_->write_checkpoint(state_, resumed_from_backup);
        checkpoint_path_ = output_->path(kCheckpointFile);
        // After the checkpoint, the record run.json is checked against: a crash between the two
        // leaves run.json behind it, which a resume reconciles (read_run_info).
        if (rules_changed) output_->write_run_info(original_experiment_, state_);
    }

    auto report = std::make_shared<GenerationReport>(
        make_generation_report(state_, selection, tally, rules_changed, new_champion));
    const double generation_wall_s = tally.generation_wall_s;
    report->generation_budget = generation_budget_;
    report->generation_wall_s = generation_wall_s;
    report->elapsed_s = state_.elapsed_s;
    report->simulations_per_s = generation_wall_s > 0.0 ? row.simulations / generation_wall_s : 0.0;
    const double per_generation = seconds_since(session_start_) / session_generations_;
    const double by_generations = (generation_budget_ - 1 - tally.generation) * per_generation;
    report->eta_s = std::max(0.0, std::min(by_generations, wall_budget_s_ - state_.elapsed_s));
    publish(std::move(report));
}

}  // namespace bhm::evo
