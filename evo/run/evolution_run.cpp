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
#include "evo/run/checkpoint.hpp"
#include "evo/run/run_lock.hpp"
#include "evo/search/afpo.hpp"
#include "evo/search/crossover.hpp"
#include "evo/search/mutation.hpp"
#include "evo/search/neat_generation.hpp"
#include "evo/search/novelty_selection.hpp"

namespace bhm::evo {

namespace fs = std::filesystem;

namespace {

double seconds_since(std::chrono::steady_clock::time_point start) {
    return std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
}

double median_fitness(const std::vector<Individual>& population) {
    if (population.empty()) return 0.0;
    std::vector<double> f;
    f.reserve(population.size());
    for (const auto& m : population)
        f.push_back(m.report.fitness);
    std::sort(f.begin(), f.end());
    const std::size_t n = f.size();
    return n % 2 == 1 ? f[n / 2] : 0.5 * (f[n / 2 - 1] + f[n / 2]);
}

//! The best member: valid first, then fitness desc, age asc, id asc.
const Individual& best_member(const std::vector<Individual>& population) {
    return *std::min_element(population.begin(), population.end(),
                             [](const Individual& a, const Individual& b) {
                                 if (a.valid != b.valid) return a.valid;
                                 if (a.report.fitness != b.report.fitness)
                                     return a.report.fitness > b.report.fitness;
                                 if (a.age != b.age) return a.age < b.age;
                                 return a.id < b.id;
                             });
}

Experiment read_original_experiment(const std::string& dir) {
    const std::string path = (fs::path(dir) / "run.json").string();
    std::ifstream in(path);
    if (!in) throw std::runtime_error(path + ": missing");
    std::stringstream text;
    text << in.rdbuf();
    nlohmann::json json;
    try {
        json = nlohmann::json::parse(text.str());
    } catch (const nlohmann::json::exception& e) {
        throw std::runtime_error(path + ": damaged, not valid JSON (" + e.what() + ")");
    }
    if (!json.is_object() || !json.contains("experiment"))
        throw std::runtime_error(path + ":experiment: missing");
    return parse_experiment(json.at("experiment"), path + ":experiment");
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
        s.original = read_original_experiment(options.out_dir);
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

void EvolutionRun::set_paused(bool paused) {
    {
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
    std::lock_guard lock(control_mutex_);
    double s = paused_s_;
    if (paused_.load()) s += seconds_since(pause_began_);
    return s;
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
    if (p.running)
        p.elapsed_s = std::max(0.0, seconds_since(start) - (paused_seconds() - paused_at_start));
    return p;
}

void EvolutionRun::progress_begin(int generation) {
    const double paused = paused_seconds();
    std::lock_guard lock(progress_mutex_);
    progress_ = GenerationProgress{true, generation, 0, 0, 0.0};
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

void EvolutionRun::request_fitness_change(const Fitness& fitness) {
    std::lock_guard lock(control_mutex_);
    pending_fitness_ = fitness;
    ++pending_serial_;
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

bool EvolutionRun::draw_random_individual(Individual& out, Rng& rng, std::int64_t id,
                                          int generation, const Constraints& constraints) const {
    const auto& e = state_.experiment;
    const int attempts = std::max(100, e.evolution.max_neutral_retries);
    for (int attempt = 0; attempt < attempts; ++attempt) {
        Genome genome = random_genome(e.evolution.cppn, rng, developer_.cppn_output_count());
        Phenotype phenotype = developer_.develop(genome);
        if (!constraint_violation(constraints, e.boundary, developer_.space(), phenotype).empty())
            continue;
        out = Individual{};
        out.id = id;
        out.born_generation = generation;
        out.genome = std::move(genome);
        out.phenotype = std::move(phenotype);
        return true;
    }
    return false;
}

StopReason EvolutionRun::run() {
    if (session_generations_ == 0) session_start_ = std::chrono::steady_clock::now();
    for (;;) {
        {
            // A signal handler cannot notify, so poll the stop flag while paused.
            std::unique_lock lock(control_mutex_);
            while (paused_.load() && !stop_.load())
                control_changed_.wait_for(lock, std::chrono::milliseconds(100));
        }
        if (stop_.load()) return StopReason::StopRequested;
        if (state_.generation + 1 >= generation_budget_) return StopReason::GenerationBudget;
        if (state_.elapsed_s >= wall_budget_s_) return StopReason::WallBudget;
        if (!run_generation()) return StopReason::StopRequested;
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
    Experiment rules = state_.experiment;
    bool rules_changed = false;
    std::uint64_t applied_serial = 0;
    {
        std::lock_guard lock(control_mutex_);
        if (pending_fitness_) {
            rules.fitness = *pending_fitness_;
            applied_serial = pending_serial_;
            rules_changed = true;
        }
    }
    std::vector<Individual> population = state_.population;
    std::optional<ChampionRecord> champion = state_.champion;
    int rules_version = state_.rules_version;
    if (rules_changed) {
        ++rules_version;
        for (auto& m : population) {
            m.valid = constraint_violation(rules.fitness.constraints, rules.boundary,
                                           developer_.space(), m.phenotype)
                          .empty();
            m.report.fitness = m.valid ? fitness_under(m.report, rules.fitness) : kInvalidFitness;
            m.valid = m.valid && !rejected_by_exploit(m.report.exploits, rules.fitness.constraints);
        }
        champion.reset();  // re-established from the re-scored population below
    }

    Rng rng;
    rng.set_state(state_.rng);
    std::int64_t next_id = state_.next_id;
    const auto& constraints = rules.fitness.constraints;

    // The algorithm's breeding step (evolution.algorithm): which members carry over into the pool
    // and which new individuals are evaluated below.
    Brood brood;
    NeatState neat = state_.neat;
    if (rules_changed && rules.evolution.algorithm == Algorithm::Neat)
        restart_species_records(population, g - 1, neat);
    switch (rules.evolution.algorithm) {
        case Algorithm::Afpo:
        case Algorithm::Novelty:  // novelty search breeds as AFPO; only its selection differs
            if (g == 0)
                breed_random(rules, g, rng, next_id, brood);
            else
                breed_afpo(rules, g, std::move(population), rng, next_id, brood);
            break;
        case Algorithm::Neat: {
            NeatBrood made;
            neat_breed(rules, developer_, g, population, neat, rng, next_id, made);
            brood.carried = std::move(made.carried);
            brood.fresh = std::move(made.fresh);
            brood.clones = made.clones;
            break;
        }
        default:
            throw std::invalid_argument(
                std::string("evolution.algorithm \"") +
                kAlgorithmNames[static_cast<int>(rules.evolution.algorithm)] +
                "\" is not built yet");
    }
    std::vector<Individual>& fresh = brood.fresh;
    const int clones = brood.clones, newcomers_skipped = brood.newcomers_skipped;

    // Results: a clone's from its parent, then the cache, then one simulation per new phenotype.
    int cache_hits = 0;
    std::vector<int> job_of(fresh.size(), -1);
    std::vector<std::size_t> jobs;
    std::vector<std::uint64_t> job_hashes;
    std::unordered_map<std::uint64_t, int> job_by_hash;
    for (std::size_t i = 0; i < fresh.size(); ++i) {
        auto& ind = fresh[i];
        if (ind.evaluated) {
            ++cache_hits;
            continue;
        }
        if (const FitnessReport* hit = state_.cache.find(ind.phenotype.hash)) {
            ind.report = *hit;
            ind.report.fitness = fitness_under(*hit, rules.fitness);
            ind.valid = !rejected_by_exploit(hit->exploits, constraints);
            ind.evaluated = true;
            ++cache_hits;
            continue;
        }
        const auto [it, inserted] =
            job_by_hash.emplace(ind.phenotype.hash, static_cast<int>(jobs.size()));
        if (inserted) {
            jobs.push_back(i);
            job_hashes.push_back(ind.phenotype.hash);
        } else {
            ++cache_hits;  // a twin of an earlier new individual this generation
        }
        job_of[i] = it->second;
    }
    std::vector<FitnessReport> results;
    EvaluationBatch batch;
    batch.rules = &rules;
    batch.cancel = &stop_;
    batch.pause = &paused_;
    batch.on_result = [this](std::size_t) { progress_count_one(); };
    for (const std::size_t i : jobs)
        batch.bodies.push_back(&fresh[i].phenotype.body);
    progress_set_total(static_cast<int>(jobs.size()));
    try {
        evaluator_->evaluate(batch, results);
    } catch (const EvaluationCancelled&) {
        return false;
    }
    int diverged = 0, ended_early = 0;
    double simulated_s = 0.0;
    for (const auto& r : results) {
        diverged += r.diverged ? 1 : 0;
        ended_early += r.ended_early ? 1 : 0;
        simulated_s += r.simulated_s;
    }
    for (std::size_t i = 0; i < fresh.size(); ++i) {
        if (job_of[i] < 0) continue;
        fresh[i].report = results[static_cast<std::size_t>(job_of[i])];
        fresh[i].evaluated = true;
        fresh[i].valid = !rejected_by_exploit(fresh[i].report.exploits, constraints);
    }

    // The algorithm's selection step: the next population, in selection order, from the carried
    // members plus the new individuals.
    std::vector<Individual> pool = std::move(brood.carried);
    const std::size_t first_new = pool.size();
    for (auto& f : fresh)
        pool.push_back(std::move(f));
    std::vector<Individual> next_population;
    std::vector<int> next_ranks;
    std::optional<NoveltySelection> novelty;
    std::vector<double> next_novelty;
    switch (rules.evolution.algorithm) {
        case Algorithm::Novelty: {
            const NoveltyArchive archive =
                g == 0 ? NoveltyArchive{{}, rules.evolution.novelty.archive_threshold}
                       : state_.novelty_archive;
            novelty = select_by_novelty(pool, first_new, archive, rules);
            for (int index : novelty->survivors) {
                const auto i = static_cast<std::size_t>(index);
                next_population.push_back(pool[i]);
                next_ranks.push_back(novelty->ranks[i]);
                next_novelty.push_back(novelty->novelty[i]);
            }
            break;
        }
        case Algorithm::Neat:
            next_population = neat_select(rules, g, std::move(pool), neat);
            next_ranks.assign(next_population.size(), 0);  // no Pareto layers in NEAT
            break;
        case Algorithm::Afpo:
        default:
            select_afpo(rules, std::move(pool), next_population, next_ranks);
            break;
    }

    const Individual& best = best_member(next_population);
    // Novelty selection may drop the fittest new individual, so its champion comes from the whole
    // pool (AFPO's and NEAT's populations keep the pool's best anyway).
    const Individual& contender = novelty ? best_member(pool) : best;
    bool new_champion = false;
    if (!champion || contender.report.fitness > champion->individual.report.fitness) {
        champion = ChampionRecord{contender, g};
        new_champion = true;
    }
    const double generation_wall_s = progress().elapsed_s;  // paused time excluded

    HistoryRow row;
    row.generation = g;
    row.evaluations = static_cast<int>(fresh.size());
    row.simulations = static_cast<int>(jobs.size());
    row.best_fitness = best.report.fitness;
    row.median_fitness = median_fitness(next_population);
    row.best_age = best.age;
    row.best_id = best.id;
    row.diverged = diverged;
    row.ended_early = ended_early;
    row.mean_simulated_s =
        results.empty() ? 0.0 : simulated_s / static_cast<double>(results.size());
    row.best_simulated_s = best.report.simulated_s;
    row.best_periodic_residual = best.report.periodic_residual;
    row.wall_s = state_.elapsed_s + generation_wall_s;
    row.rules_version = rules_version;
    row.best_exploits = best.report.exploits;
    for (const auto& m : next_population)
        row.flagged_members += m.report.exploits.any() ? 1 : 0;
    if (rules.evolution.algorithm == Algorithm::Neat)
        row.species = static_cast<int>(neat.species.size());
    if (novelty) {
        NoveltyRow n;
        std::vector<double> sorted = next_novelty;
        std::sort(sorted.begin(), sorted.end());
        if (!sorted.empty()) {
            const std::size_t m = sorted.size();
            n.best_novelty = sorted.back();
            n.median_novelty = m % 2 == 1 ? sorted[m / 2] : 0.5 * (sorted[m / 2 - 1] + sorted[m / 2]);
        }
        n.archive_size = static_cast<int>(novelty->archive.entries.size());
        n.archive_added = novelty->added;
        n.archive_threshold = novelty->archive.threshold;
        n.champion_fitness = champion->individual.report.fitness;
        row.novelty = n;
    }

    // Commit.
    state_.experiment = rules;
    state_.generation = g;
    state_.next_id = next_id;
    state_.rng = rng.state();
    state_.rules_version = rules_version;
    state_.elapsed_s = row.wall_s;
    state_.population = std::move(next_population);
    state_.pareto_rank = std::move(next_ranks);
    state_.champion = champion;
    state_.neat = std::move(neat);
    if (novelty) state_.novelty_archive = std::move(novelty->archive);
    state_.history.push_back(row);
    if (rules_changed) state_.rule_changes.push_back({g, rules.fitness});
    for (std::size_t j = 0; j < jobs.size(); ++j)
        state_.cache.insert(job_hashes[j], results[j]);
    {
        std::lock_guard lock(control_mutex_);
        if (rules_changed && pending_serial_ == applied_serial) pending_fitness_.reset();
    }
    ++session_generations_;

    if (output_) {
        if (rules_changed) output_->write_run_info(original_experiment_, state_);
        output_->write_fitness_csv(state_.history);
        if (new_champion) output_->write_champion(rules, *state_.champion);
        output_->write_checkpoint(state_);
        checkpoint_path_ = output_->path(kCheckpointFile);
    }

    auto report = std::make_shared<GenerationReport>();
    report->generation = g;
    report->generation_budget = generation_budget_;
    report->measure = rules.fitness.measure;
    report->rules_version = rules_version;
    report->rules_changed = rules_changed;
    report->best_fitness = row.best_fitness;
    report->median_fitness = row.median_fitness;
    report->champion = *state_.champion;
    report->new_champion = new_champion;
    report->species = row.species;
    report->novelty = row.novelty;
    const auto species_of = species_of_members(state_.neat, state_.population.size());
    for (std::size_t k = 0; k < state_.population.size(); ++k) {
        const auto& m = state_.population[k];
        report->population.push_back(
            {m.id, m.report.fitness, m.age, m.phenotype.voxels,
             m.phenotype.voxels > 0
                 ? static_cast<double>(m.phenotype.active_voxels) / m.phenotype.voxels
                 : 0.0,
             state_.pareto_rank[k], m.report.diverged, m.valid, m.report.exploits,
             species_of[k] >= 0 ? state_.neat.species[static_cast<std::size_t>(species_of[k])].id
                                : 0});
        if (k < next_novelty.size()) report->population.back().novelty = next_novelty[k];
    }
    report->evaluations = row.evaluations;
    report->simulations = row.simulations;
    report->cache_hits = cache_hits;
    report->clones = clones;
    report->diverged = diverged;
    report->newcomers_skipped = newcomers_skipped;
    report->generation_wall_s = generation_wall_s;
    report->elapsed_s = state_.elapsed_s;
    report->simulations_per_s = generation_wall_s > 0.0 ? row.simulations / generation_wall_s : 0.0;
    const double per_generation = seconds_since(session_start_) / session_generations_;
    const double by_generations = (generation_budget_ - 1 - g) * per_generation;
    report->eta_s = std::max(0.0, std::min(by_generations, wall_budget_s_ - state_.elapsed_s));
    publish(std::move(report));
    return true;
}

void EvolutionRun::breed_random(const Experiment& rules, int g, Rng& rng, std::int64_t& next_id,
                                Brood& out) const {
    for (int i = 0; i < rules.evolution.population; ++i) {
        Individual ind;
        if (!draw_random_individual(ind, rng, next_id, g, rules.fitness.constraints))
            throw std::runtime_error(
                "no valid random individual in " +
                std::to_string(std::max(100, rules.evolution.max_neutral_retries)) +
                " draws: the constraints may be too strict for this workspace");
        ++next_id;
        out.fresh.push_back(std::move(ind));
    }
}

void EvolutionRun::breed_afpo(const Experiment& rules, int g, std::vector<Individual> population,
                              Rng& rng, std::int64_t& next_id, Brood& brood) const {
    const auto& constraints = rules.fitness.constraints;
    std::vector<Individual>& fresh = brood.fresh;
    int& clones = brood.clones;
    for (auto& m : population)
        ++m.age;
    const double crossover_rate = rules.evolution.crossover_rate;
    for (std::size_t p = 0; p < population.size(); ++p) {
        const Individual& parent = population[p];
        // Rate 0 draws nothing, so mutation-only runs keep the paper's random stream.
        const Individual* mate = nullptr;
        if (crossover_rate > 0.0 && population.size() > 1 && rng.uniform() < crossover_rate) {
            auto m = static_cast<std::size_t>(rng.index(static_cast<int>(population.size()) - 1));
            mate = &population[m >= p ? m + 1 : m];  // any member but the parent
        }
        auto out = mate ? cross_then_mutate(parent.genome, mate->genome, parent.phenotype,
                                            developer_, constraints, rules.evolution.cppn,
                                            rules.evolution.max_neutral_retries, rng)
                        : mutate_until_new(parent.genome, parent.phenotype, developer_,
                                           constraints, rules.evolution.cppn,
                                           rules.evolution.max_neutral_retries, rng);
        Individual child;
        child.id = next_id++;
        child.parent_id = parent.id;
        // AFPO: an offspring is as old as its oldest parent.
        child.age = mate && !out.cloned ? std::max(parent.age, mate->age) : parent.age;
        child.born_generation = g;
        child.genome = std::move(out.genome);
        child.phenotype = std::move(out.phenotype);
        if (out.cloned) {  // same phenotype as the parent: same result
            child.report = parent.report;
            child.evaluated = parent.evaluated;
            child.valid = parent.valid;
            ++clones;
        }
        fresh.push_back(std::move(child));
    }
    Individual newcomer;
    if (draw_random_individual(newcomer, rng, next_id, g, constraints)) {
        ++next_id;
        fresh.push_back(std::move(newcomer));
    } else {
        ++brood.newcomers_skipped;
    }
    // AFPO's pool is the whole aged population plus its new individuals.
    brood.carried = std::move(population);
}

void EvolutionRun::select_afpo(const Experiment& rules, std::vector<Individual> pool,
                               std::vector<Individual>& next_population,
                               std::vector<int>& next_ranks) const {
    std::vector<AfpoObjectives> objectives;
    objectives.reserve(pool.size());
    for (const auto& m : pool)
        objectives.push_back({m.report.fitness, m.age, m.phenotype.active_voxels, m.id});
    const bool third_objective = rules.fitness.minimize_active_voxels;
    const auto survivors = select_survivors(objectives, rules.evolution.population, third_objective);
    const auto ranks = pareto_ranks(objectives, third_objective);
    for (int index : survivors) {
        next_population.push_back(pool[static_cast<std::size_t>(index)]);
        next_ranks.push_back(ranks[static_cast<std::size_t>(index)]);
    }
}

}  // namespace bhm::evo
