#include "evo/evaluate/evaluator.hpp"

#include "evo/evaluate/worker_pool.hpp"

namespace bhm::evo {

void ThreadEvaluator::evaluate(const EvaluationBatch& batch, std::vector<FitnessReport>& results) {
    results.assign(batch.bodies.size(), FitnessReport{});
    parallel_for(static_cast<int>(batch.bodies.size()), threads_, [&](int j) {
        const auto index = static_cast<std::size_t>(j);
        results[index] = evaluate_body(*batch.rules, *batch.bodies[index],
                                       EvaluationControl{batch.cancel, batch.pause});
        if (batch.on_result) batch.on_result(index);
    });
}

}  // namespace bhm::evo
