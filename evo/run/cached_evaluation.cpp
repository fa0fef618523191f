#include "evo/run/cached_evaluation.hpp"

#include <unordered_map>

#include "evo/evaluate/constraints.hpp"

namespace bhm::evo {

CachedEvaluation evaluate_fresh(std::vector<Individual>& fresh, const Experiment& rules,
                                const FitnessCache& cache, Evaluator& evaluator,
                                EvaluationBatch batch, const std::function<void(int)>& on_total) {
    const auto& constraints = rules.fitness.constraints;
    CachedEvaluation out;
    std::vector<int> job_of(fresh.size(), -1);
    std::vector<std::size_t> jobs;
    std::unordered_map<std::uint64_t, int> job_by_hash;
    for (std::size_t i = 0; i < fresh.size(); ++i) {
        auto& ind = fresh[i];
        if (ind.evaluated) {
            ++out.cache_hits;
            continue;
        }
        if (const FitnessReport* hit = cache.find(ind.phenotype.hash)) {
            ind.report = *hit;
            ind.report.fitness = fitness_under(*hit, rules.fitness);
            ind.valid = !rejected_by_exploit(hit->exploits, constraints);
            ind.evaluated = true;
            ++out.cache_hits;
            continue;
        }
        const auto [it, inserted] =
            job_by_hash.emplace(ind.phenotype.hash, static_cast<int>(jobs.size()));
        if (inserted) {
            jobs.push_back(i);
            out.simulated_hashes.push_back(ind.phenotype.hash);
        } else {
            ++out.cache_hits;  // a twin of an earlier new individual this generation
        }
        job_of[i] = it->second;
    }
    batch.rules = &rules;
    batch.bodies.clear();
    for (const std::size_t i : jobs)
        batch.bodies.push_back(&fresh[i].phenotype.body);
    if (on_total) on_total(static_cast<int>(jobs.size()));
    evaluator.evaluate(batch, out.simulated_reports);
    for (const auto& r : out.simulated_reports)
        out.diverged += r.diverged ? 1 : 0;
    for (std::size_t i = 0; i < fresh.size(); ++i) {
        if (job_of[i] < 0) continue;
        fresh[i].report = out.simulated_reports[static_cast<std::size_t>(job_of[i])];
        fresh[i].evaluated = true;
        fresh[i].valid = !rejected_by_exploit(fresh[i].report.exploits, constraints);
    }
    return out;
}

}  // namespace bhm::evo
