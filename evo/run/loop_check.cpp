#include "evo/run/loop_check.hpp"

#include <algorithm>
#include <chrono>
#include <unordered_set>

#include "evo/evaluate/fitness.hpp"

namespace bhm::evo {

bool is_check_generation(const LoopVerifySettings& settings, int generation) {
    return settings.enabled() && generation >= 0 &&
           (generation + 1) % settings.every_generations == 0;
}

int landing_generation(const LoopVerifySettings& settings, int picked) {
    return picked + std::max(1, settings.every_generations);
}

LoopCheckIndex index_checks(const std::vector<LoopCheck>& checks) {
    LoopCheckIndex index;
    for (const auto& c : checks)
        index[c.hash] = &c;
    return index;
}

std::vector<LoopCheckRequest> pick_for_check(const std::vector<Individual>& population,
                                             const Individual* champion,
                                             const LoopVerifySettings& settings,
                                             const LoopCheckIndex& done) {
    std::vector<const Individual*> candidates;
    if (champion) candidates.push_back(champion);
    for (const auto& m : population)
        candidates.push_back(&m);
    // best_member's order (generation_report.cpp), so the champion and "the best" agree.
    std::stable_sort(candidates.begin(), candidates.end(),
                     [](const Individual* a, const Individual* b) {
                         if (a->valid != b->valid) return a->valid;
                         if (a->report.fitness != b->report.fitness)
                             return a->report.fitness > b->report.fitness;
                         if (a->age != b->age) return a->age < b->age;
                         return a->id < b->id;
                     });
    std::vector<LoopCheckRequest> picks;
    std::unordered_set<std::uint64_t> seen;
    for (const Individual* m : candidates) {
        if (static_cast<int>(picks.size()) >= settings.top_k) break;
        if (!m->evaluated || !m->valid || m->report.diverged) continue;
        if (!seen.insert(m->phenotype.hash).second || done.count(m->phenotype.hash)) continue;
        picks.push_back({m->id, m->phenotype.hash, m->phenotype.body});
    }
    return picks;
}

double penalty_factor(const LoopCheck& check) {
    if (check.outcome != LoopCheckOutcome::Differs || !(check.engine_score > 0.0)) return 1.0;
    return std::clamp(check.fem_score / check.engine_score, 0.0, 1.0);
}

void apply_loop_check(Individual& member, const Experiment& rules, const LoopCheckIndex& checks) {
    const auto& settings = rules.evolution.verify;
    if (!member.evaluated || !member.valid || settings.policy == VerifyPolicy::Flag) return;
    const auto it = checks.find(member.phenotype.hash);
    if (it == checks.end()) return;
    const LoopCheck& check = *it->second;
    if (settings.policy == VerifyPolicy::Reject) {
        if (check.compared() && check.worst > settings.tolerance) member.valid = false;
        return;
    }
    // Penalise: from the measures, so that a member penalised before is not penalised twice.
    const double fitness = fitness_under(member.report, rules.fitness);
    if (fitness > 0.0) member.report.fitness = fitness * penalty_factor(check);
}

LoopCheckJob::LoopCheckJob(std::shared_ptr<ContinuumChecker> checker, Experiment rules,
                           int generation, std::vector<LoopCheckRequest> picks,
                           std::string out_dir)
    : checker_(std::move(checker)),
      rules_(std::move(rules)),
      generation_(generation),
      picks_(std::move(picks)),
      out_dir_(std::move(out_dir)) {
    thread_ = std::thread([this] { work(); });
}

LoopCheckJob::~LoopCheckJob() {
    cancel();
    if (thread_.joinable()) thread_.join();
}

void LoopCheckJob::work() {
    struct Finished {  // on every way out
        std::atomic<bool>& flag;
        ~Finished() { flag.store(true); }
    } finished{finished_};
    for (const auto& pick : picks_) {
        std::optional<LoopCheck> result;
        try {
            result = checker_->check(rules_, pick, out_dir_, cancel_);
        } catch (const std::exception& e) {  // a checker should not throw; one body's loss
            result = LoopCheck{};
            result->outcome = LoopCheckOutcome::Failed;
            result->verdict = e.what();
        }
        if (!result || cancel_.load()) {
            cancelled_ = true;
            return;
        }
        result->generation = generation_;
        result->id = pick.id;
        result->hash = pick.hash;
        results_.push_back(std::move(*result));
    }
}

std::optional<std::vector<LoopCheck>> LoopCheckJob::join(const std::atomic<bool>* stop) {
    while (!finished_.load()) {
        if (stop && stop->load()) cancel();
        std::this_thread::sleep_for(std::chrono::milliseconds(10));
    }
    if (thread_.joinable()) thread_.join();
    if (cancelled_) return std::nullopt;
    return results_;
}

LoopCheckRow loop_check_row(const std::vector<LoopCheck>& landed, const Individual* champion,
                            const LoopCheckIndex& all) {
    LoopCheckRow row;
    row.verified = static_cast<int>(landed.size());
    for (const auto& c : landed)
        if (c.compared())
            row.worst_difference = std::max(row.worst_difference.value_or(0.0), c.worst);
    if (champion) {
        const auto it = all.find(champion->phenotype.hash);
        if (it != all.end() && it->second->compared())
            row.champion_agrees = it->second->outcome == LoopCheckOutcome::Agrees;
    }
    return row;
}

}  // namespace bhm::evo
