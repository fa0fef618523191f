// bhm robustness: a table of bodies against controllers (issue 44), each cell one full
// evaluation under the experiment's fitness (evo/evaluate/robustness.hpp), written as
// robustness.csv and a heatmap robustness.png (app/cli/robustness_plot.hpp).
#include <cstdio>
#include <filesystem>
#include <iostream>
#include <mutex>
#include <stdexcept>
#include <string>
#include <vector>

#include "app/cli/arg_parser.hpp"
#include "app/cli/commands.hpp"
#include "app/cli/png_encode.hpp"
#include "app/cli/problem_report.hpp"
#include "app/cli/robustness_plot.hpp"
#include "evo/evaluate/robustness.hpp"
#include "evo/experiment/experiment_io.hpp"

namespace bhm::app {

namespace {

const char* const kSummary =
    "Evaluates every BODY under every controller of --controllers, each pair one full evaluation\n"
    "under EXPERIMENT's fitness (the evaluation of `bhm simulate` and of a run: settle_s +\n"
    "evaluate_s, fitness.measure, the exploit constraints), and writes into DIR:\n"
    "  robustness.csv  a header \"body,C1,...,Cm\", then one row per body: its fitness under each\n"
    "                  controller (-1 diverged, -2 rejected by a reject_* exploit constraint)\n"
    "  robustness.png  the same table as a heatmap (rows bodies, columns controllers; dark blue\n"
    "                  the lowest fitness, yellow the highest, grey crossed cells diverged or\n"
    "                  rejected)\n"
    "A row is one morphology under several control methods; a column is one controller over a\n"
    "set of morphologies (the reverse study: give one controller and many bodies).\n"
    "The body is framed, then painted by the controller, which replaces any controller its\n"
    "file carries (docs/experiment-format.md, \"Controllers\").\n"
    "\n"
    "exit status: 0 ok, 1 invalid or missing input (each problem one line naming file and "
    "field),\n"
    "2 usage error.";

std::vector<std::string> split_list(const std::string& text) {
    std::vector<std::string> items(1);
    for (const char c : text) {
        if (c == ',')
            items.emplace_back();
        else
            items.back() += c;
    }
    return items;
}

int robustness(ArgParser& args) {
    const auto& positionals = args.positionals();
    const std::string experiment_path = positionals.at(0);
    if (positionals.size() < 2) throw UsageError("give at least one BODY.json");
    if (!args.has("--controllers"))
        throw UsageError(
            "missing --controllers C1,C2,... (uniform, random, random:SEED, wave, "
            "a controller file or a run directory)");
    const std::string out_dir = args.get("--out", "robustness-out");
    const long long threads = args.get_int("--threads", 0);
    if (threads < 0) throw UsageError("--threads must be >= 0");

    // Every body is read against the experiment before any problem is reported.
    evo::Experiment experiment;
    std::vector<evo::Body> bodies;
    std::vector<std::string> labels(positionals.begin() + 1, positionals.end());
    std::vector<evo::Problem> problems;
    for (const std::string& body_path : labels) {
        try {
            auto loaded = evo::load_experiment_and_body(experiment_path, body_path);
            if (bodies.empty() && problems.empty()) say_library_warnings(loaded.experiment);
            experiment = std::move(loaded.experiment);
            bodies.push_back(std::move(*loaded.body));
        } catch (const evo::ValidationError& e) {
            for (const auto& p : e.problems) {
                // The experiment's own problems once, not once per body.
                bool seen = false;
                for (const auto& q : problems)
                    seen =
                        seen || (q.file == p.file && q.field == p.field && q.message == p.message);
                if (!seen) problems.push_back(p);
            }
        }
    }
    if (!problems.empty()) return report_problems(problems);

    std::vector<evo::RobustnessController> controllers;
    for (const std::string& item : split_list(args.get("--controllers"))) {
        try {
            controllers.push_back(
                evo::resolve_robustness_controller(item, experiment.evolution.cppn.weight_range));
        } catch (const std::invalid_argument& e) {
            throw std::runtime_error(std::string("--controllers: ") + e.what());
        }
    }

    const int cells = static_cast<int>(bodies.size() * controllers.size());
    std::cerr << "bhm robustness: " << bodies.size() << " bodies x " << controllers.size()
              << " controllers = " << cells << " evaluations\n";
    std::mutex progress_mutex;
    const evo::RobustnessTable table = evo::evaluate_robustness(
        experiment, bodies, labels, controllers,
        threads > 0 ? static_cast<int>(threads) : experiment.evolution.threads,
        [&](int done, int total) {
            const std::lock_guard lock(progress_mutex);
            std::cerr << "bhm robustness: " << done << "/" << total << " evaluated\n";
        });

    std::filesystem::create_directories(out_dir);
    const std::string csv_path = (std::filesystem::path(out_dir) / "robustness.csv").string();
    const std::string png_path = (std::filesystem::path(out_dir) / "robustness.png").string();
    evo::write_file_atomically(csv_path, evo::robustness_csv(table));
    if (!png_available()) {
        // The table is still worth having; an earlier run's heatmap would not match it.
        std::filesystem::remove(png_path);
        std::cerr << "bhm robustness: warning: bhm was built without libpng, so " << png_path
                  << " is not written\n";
        std::cout << "wrote " << csv_path << std::endl;
        return 0;
    }
    const HeatmapScale scale = write_robustness_heatmap(png_path, table);
    char line[200];
    std::snprintf(line, sizeof line, "fitness %.4g .. %.4g; wrote ", scale.lo, scale.hi);
    std::cout << line << csv_path << " and " << png_path << std::endl;
    return 0;
}

}  // namespace

int cmd_robustness(const Args& args) {
    ArgParser parser("robustness",
                     "EXPERIMENT.json BODY.json... --controllers C1,C2,... [--out DIR]", kSummary);
    parser.positional("EXPERIMENT.json", "the experiment (docs/experiment-format.md)")
        .positional("BODY.json", "the bodies, one row each", true, true)
        .option("--controllers", "C1,C2,...",
                "the columns, comma-separated: uniform, wave, random (seed 1), random:SEED, a "
                "controller file (controller.json) or a run directory (its champion's "
                "controller.json) (required)")
        .option("--out", "DIR", "output directory (default: ./robustness-out)", PathRole::OutputDir)
        .option("--threads", "N", "worker threads (default 0: evolution.threads, else all)");
    return run_command(parser, args, robustness);
}

}  // namespace bhm::app
