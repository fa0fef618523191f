#include "evo/run/cached_evaluation.hpp"

#include <span>
#include <unordered_map>

#include "evo/evaluate/constraints.hpp"
#include "evo/genome/controller.hpp"

namespace bhm::evo {

FitnessReport mean_over_controllers(std::span<const FitnessReport> reports, const Fitness& rules) {
    FitnessReport out = reports.front();
    out.measures = {};
    out.simulated_s = 0.0;
    out.steps = 0;
    out.sim_wall_s = 0.0;
    for (const FitnessReport& r : reports) {
        for (std::size_t m = 0; m < out.measures.size(); ++m)
            out.measures[m] += r.measures[m] / static_cast<double>(reports.size());
        if (r.diverged && !out.diverged) {
            out.diverged = true;
            out.divergence_reason = r.divergence_reason;
        }
        out.ended_early = out.ended_early && r.ended_early;
        out.simulated_s += r.simulated_s;
        out.steps += r.steps;
        out.sim_wall_s += r.sim_wall_s;
    }
    out.fitness = fitness_under(out, rules);
    return out;
}

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
    // fixed_controllers (issue 44): every body once under each controller of the set.
    const auto& controllers = rules.evolution.controller.controllers;
    const bool per_controller =
        rules.evolution.controller.mode == ControllerMode::FixedControllers && !controllers.empty();
    std::vector<Body> painted;
    if (per_controller) {
        painted.reserve(jobs.size() * controllers.size());
        for (const std::size_t i : jobs)
            for (const ControllerEntry& entry : controllers) {
                painted.push_back(fresh[i].phenotype.body);
                paint_controller_entry(entry, rules.evolution.cppn.weight_range, rules.materials,
                                       painted.back());
            }
        for (const Body& body : painted)
            batch.bodies.push_back(&body);
    } else {
        for (const std::size_t i : jobs)
            batch.bodies.push_back(&fresh[i].phenotype.body);
    }
    if (on_total) on_total(static_cast<int>(batch.bodies.size()));
    if (per_controller) {
        if (batch.on_result) {  // progress per body, not per controller
            auto per_body = batch.on_result;
            const std::size_t n = controllers.size();
            batch.on_result = [per_body, n](std::size_t index) {
                if (index % n == n - 1) per_body(index / n);
            };
        }
        std::vector<FitnessReport> each;
        evaluator.evaluate(batch, each);
        for (std::size_t j = 0; j < jobs.size(); ++j)
            out.simulated_reports.push_back(mean_over_controllers(
                std::span(each).subspan(j * controllers.size(), controllers.size()),
                rules.fitness));
    } else {
        evaluator.evaluate(batch, out.simulated_reports);
    }
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
