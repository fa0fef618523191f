#pragma once
// Robustness tables (issue 44): bodies B1..Bn against controllers C1..Cm, each cell one full
// evaluation (evaluate_body) of that body driven by that controller, scored under the
// experiment's fitness. Read by row, a table is one morphology under several control methods;
// read by column, one controller over a set of morphologies (the two robustness measures of the
// controller studies, arXiv 2408.09107). A cell is exactly what `bhm simulate` evaluates for the
// body file of robustness_cell_body: the body framed, then painted by the controller, as the
// fixed_controllers mode of a run paints its bodies (evo/run/cached_evaluation.cpp).
#include <atomic>
#include <functional>
#include <string>
#include <vector>

#include "evo/evaluate/fitness.hpp"
#include "evo/experiment/experiment.hpp"

namespace bhm::evo {

//! A column of the table: its label (the command-line item as given) and the controller.
struct RobustnessController {
    std::string label;
    ControllerEntry entry;
};

//! One --controllers item: "uniform", "wave", "random" (seed 1), "random:SEED", a controller file
//! (controller.json, docs/experiment-format.md "Controllers") or a run directory (its champion's
//! controller.json). A controller file's genome is checked here against weight_range. Throws
//! std::invalid_argument "ITEM: reason" (naming the file and field for a bad controller file).
RobustnessController resolve_robustness_controller(const std::string& item, double weight_range);

//! The body a cell simulates: body framed (apply_frame_and_overrides), then painted by the
//! controller (paint_controller_entry; it replaces any controller the body file carried).
Body robustness_cell_body(const Experiment& experiment, const Body& body,
                          const ControllerEntry& controller);

struct RobustnessTable {
    std::vector<std::string> bodies;       //!< row labels (the body files)
    std::vector<std::string> controllers;  //!< column labels
    //! Row-major (body, controller): fitness under the experiment's fitness rules
    //! (fitness_under; kDivergedFitness for a diverged cell, kInvalidFitness for a rejected one).
    std::vector<double> fitness;
    std::vector<FitnessReport> reports;  //!< the same order; empty when read from a CSV
    double at(std::size_t body, std::size_t controller) const {
        return fitness[body * controllers.size() + controller];
    }
};

//! Evaluates every cell on `threads` worker threads (evo/evaluate/worker_pool.hpp; 0 = all
//! hardware threads). The result does not depend on the thread count. on_cell(done, total) is
//! called after each cell, from any worker thread (serialise it yourself). A raised `cancel`
//! (the studio's Cancel) stops every cell within milliseconds and throws EvaluationCancelled.
RobustnessTable evaluate_robustness(const Experiment& experiment, const std::vector<Body>& bodies,
                                    const std::vector<std::string>& body_labels,
                                    const std::vector<RobustnessController>& controllers,
                                    int threads, const std::function<void(int, int)>& on_cell = {},
                                    const std::atomic<bool>* cancel = nullptr);

//! robustness.csv: a header "body,C1,...,Cm", then one row per body "B,f11,...,f1m"; numbers
//! with 17 significant digits (they read back bit-identical), labels quoted as RFC 4180 when
//! they hold a comma, quote or line break.
std::string robustness_csv(const RobustnessTable& table);
//! Reads robustness_csv's text back (labels and fitness). Throws std::invalid_argument naming
//! the line.
RobustnessTable parse_robustness_csv(const std::string& text);

}  // namespace bhm::evo
