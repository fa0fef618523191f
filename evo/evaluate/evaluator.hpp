#pragma once
// Where the simulations of a generation run. EvolutionRun hands its evaluator one batch per
// generation: the rules (the experiment in force) and the framed bodies that need a simulation;
// the evaluator fills one FitnessReport per body, in the batch's order. Because evaluate_body is a
// pure function of (experiment, body), any implementation that returns evaluate_body's reports
// gives the same run whatever it runs on or in which order it finishes.
//
// Implementations: ThreadEvaluator (this process's worker threads, the default) and the MPI front
// end in app/ (other ranks, app/mpi_evaluator.*). evo/ itself never links MPI.
#include <atomic>
#include <cstddef>
#include <functional>
#include <stdexcept>
#include <vector>

#include "evo/evaluate/fitness.hpp"
#include "evo/experiment/experiment.hpp"

namespace bhm::evo {

struct EvaluationBatch {
    const Experiment* rules = nullptr;  //!< the experiment every body is simulated under
    std::vector<const Body*> bodies;    //!< framed, workspace-sized bodies
    //! Raised to abandon the batch: evaluate() then throws EvaluationCancelled.
    const std::atomic<bool>* cancel = nullptr;
    //! Raised to hold the simulations in flight where they are until it is lowered (or cancel
    //! is raised); an evaluator that cannot pause may ignore it.
    const std::atomic<bool>* pause = nullptr;
    //! Called once per body as its result lands (from any thread, concurrently): progress only.
    std::function<void(std::size_t index)> on_result;
};

//! Thrown by an evaluator that lost part of itself for good (a rank that died or hung). The
//! generation is abandoned, the run's state stays at the last complete generation (whose
//! checkpoint is on disk), and a resumed run continues exactly as if nothing had happened.
struct EvaluatorLost : std::runtime_error {
    using std::runtime_error::runtime_error;
};

class Evaluator {
  public:
    virtual ~Evaluator() = default;
    //! Fills results (resized to bodies.size()) with evaluate_body(*rules, *bodies[i]). Throws
    //! EvaluationCancelled when batch.cancel is raised; any other exception (a lost rank, a
    //! simulation error) abandons the generation and propagates to the run's caller.
    virtual void evaluate(const EvaluationBatch& batch, std::vector<FitnessReport>& results) = 0;
    //! Simulations this evaluator runs at once (for messages and benchmarks).
    virtual int concurrency() const = 0;
};

//! Runs the batch on this process's worker pool: `threads` threads take the next body in turn.
class ThreadEvaluator final : public Evaluator {
  public:
    explicit ThreadEvaluator(int threads) : threads_(threads < 1 ? 1 : threads) {}
    void evaluate(const EvaluationBatch& batch, std::vector<FitnessReport>& results) override;
    int concurrency() const override { return threads_; }

  private:
    int threads_;
};

}  // namespace bhm::evo
