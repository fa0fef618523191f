#include "evo/run/cached_evaluation.hpp"

#include <algorithm>
#include <span>
#include <unordered_map>

#include "evo/evaluate/constraints.hpp"
#include "evo/genome/controller.hpp"

namespace bhm::evo {

namespace {

// Each flag raised when any controller's run raised it, with the measure of the first run that
// raised it (the first run's where none did), so that the measure shown explains the flag.
ExploitReport union_of_exploits(std::span<const FitnessReport> reports) {
    ExploitReport out = reports.front().exploits;
    bool detached = out.detached_motion, tentacle = out.tentacle, escaped = out.escaped;
    for (const FitnessReport& r : reports) {
        const ExploitReport& e = r.exploits;
        out.checked = out.checked && e.checked;
        out.motion_voxels = std::max(out.motion_voxels, e.motion_voxels);
        if (e.escaped && !escaped) {
            escaped = out.escaped = true;
            out.unanchored_fraction = e.unanchored_fraction;
            out.held_voxels = e.held_voxels;
        }
        if (e.detached_motion && !detached) {
            detached = out.detached_motion = true;
            out.base_motion_ratio = e.base_motion_ratio;
        }
        if (e.tentacle && !tentacle) {
            tentacle = out.tentacle = true;
            out.thin_share = e.thin_share;
            out.thin_voxels = e.thin_voxels;
        }
    }
    return out;
}

// The element-wise mean of the descriptors (one length, the same sample times); empty when any
// run has none (it diverged or never reached the end, as a single diverged run's is empty).
std::vector<double> mean_behaviour(std::span<const FitnessReport> reports) {
    const std::size_t length = reports.front().behaviour.size();
    for (const FitnessReport& r : reports)
        if (r.behaviour.empty() || r.behaviour.size() != length) return {};
    std::vector<double> out(length, 0.0);
    for (const FitnessReport& r : reports)
        for (std::size_t k = 0; k < length; ++k)
            out[k] += r.behaviour[k] / static_cast<double>(reports.size());
    return out;
}

}  // namespace

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
    out.exploits = union_of_exploits(reports);
    out.behaviour = mean_behaviour(reports);
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
