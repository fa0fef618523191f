// Analysis > Robustness's actions (robustness_actions.hpp).
#include "app/gui/actions/robustness_actions.hpp"

#include <cstdio>
#include <filesystem>
#include <stdexcept>

#include "app/cli/png_encode.hpp"
#include "app/cli/robustness_plot.hpp"
#include "app/gui/actions/studio_actions.hpp"
#include "evo/experiment/experiment_io.hpp"

namespace bhm::app::gui {

namespace {

void make_parent(const std::string& path) {
    const auto parent = std::filesystem::path(path).parent_path();
    if (!parent.empty()) std::filesystem::create_directories(parent);
}

}  // namespace

const evo::Experiment& robustness_experiment(const Studio& s) {
    // An idle session's snapshot (no run yet) has no folder and an empty experiment.
    const bool run_shown = s.run.snapshot && !s.run.snapshot->run_dir.empty();
    return run_shown ? s.run.snapshot->experiment : s.document.experiment();
}

std::vector<std::string> split_robustness_items(const std::string& text) {
    std::vector<std::string> items(1);
    for (const char c : text) {
        if (c == ',')
            items.emplace_back();
        else
            items.back() += c;
    }
    // Spaces around an item are the typist's, not part of a file name's ends.
    for (auto& item : items) {
        const auto first = item.find_first_not_of(" \t");
        const auto last = item.find_last_not_of(" \t");
        item = first == std::string::npos ? "" : item.substr(first, last - first + 1);
    }
    if (items.size() == 1 && items[0].empty()) items.clear();
    return items;
}

RobustnessRequest robustness_request(const Studio& s) {
    RobustnessRequest request;
    request.experiment = robustness_experiment(s);
    for (const ChampionEntry& e : s.run.champion_history.entries()) {
        if (!s.robustness.champions.count(e.generation)) continue;
        request.bodies.push_back(*load_champion_body(e.path));  // throws naming the file
        request.body_labels.push_back("champion gen " + std::to_string(e.generation) + " #" +
                                      std::to_string(e.id));
    }
    std::vector<evo::Problem> problems;
    for (const std::string& path : split_robustness_items(s.robustness.body_files)) {
        if (path.empty()) throw std::runtime_error("body files: an empty name (two commas?)");
        try {
            evo::Body body = evo::load_body(path);
            auto more = evo::validate_body_against(body, request.experiment, path);
            problems.insert(problems.end(), more.begin(), more.end());
            request.bodies.push_back(std::move(body));
            request.body_labels.push_back(path);
        } catch (const evo::ValidationError& e) {
            problems.insert(problems.end(), e.problems.begin(), e.problems.end());
        }
    }
    if (!problems.empty()) {
        throw std::runtime_error(
            problems.front().to_string() +
            (problems.size() > 1 ? " (and " + std::to_string(problems.size() - 1) + " more)" : ""));
    }
    if (request.bodies.empty())
        throw std::runtime_error("robustness: pick a champion or give a body file");
    for (const std::string& item : split_robustness_items(s.robustness.controllers)) {
        try {
            request.controllers.push_back(evo::resolve_robustness_controller(
                item, request.experiment.evolution.cppn.weight_range));
        } catch (const std::invalid_argument& e) {
            throw std::runtime_error(std::string("controllers: ") + e.what());
        }
    }
    if (request.controllers.empty())
        throw std::runtime_error("robustness: give at least one controller (uniform, wave, ...)");
    return request;
}

bool start_robustness(Studio& s) {
    if (s.robustness.runner.running()) {
        set_status(s, "robustness: a table is being evaluated (Cancel it first)", true);
        return false;
    }
    try {
        RobustnessRequest request = robustness_request(s);
        const std::size_t cells = request.bodies.size() * request.controllers.size();
        const std::size_t rows = request.bodies.size(), cols = request.controllers.size();
        s.robustness.runner.start(std::move(request));
        set_status(s, "robustness: " + std::to_string(rows) + " bodies x " + std::to_string(cols) +
                          " controllers = " + std::to_string(cells) + " evaluations");
        return true;
    } catch (const std::exception& e) {
        set_status(s, e.what(), true);
        return false;
    }
}

void cancel_robustness(Studio& s) {
    s.robustness.runner.cancel();
}

void update_robustness(Studio& s) {
    auto& r = s.robustness;
    if (r.runner.version() == r.state_version) return;
    r.state_version = r.runner.version();
    r.state = r.runner.state();
    const auto& st = r.state;
    if (!st || st->phase == RobustnessPhase::Running || st->job == r.job_reported) return;
    r.job_reported = st->job;
    r.shown_body = r.shown_controller = -1;
    char line[160];
    if (st->phase == RobustnessPhase::Finished) {
        std::snprintf(line, sizeof line, "robustness: %d evaluations in %.1f s", st->total,
                      st->elapsed_s);
        set_status(s, line);
    } else if (st->phase == RobustnessPhase::Cancelled) {
        std::snprintf(line, sizeof line, "robustness cancelled after %d of %d evaluations",
                      st->done, st->total);
        set_status(s, line);
    } else {
        set_status(s, "robustness: " + st->error, true);
    }
}

const evo::RobustnessTable* robustness_table(const Studio& s) {
    const auto& st = s.robustness.state;
    return st && st->phase == RobustnessPhase::Finished && st->table ? st->table.get() : nullptr;
}

bool show_robustness_cell(Studio& s, std::size_t body, std::size_t controller) {
    const evo::RobustnessTable* table = robustness_table(s);
    if (!table || body >= table->bodies.size() || controller >= table->controllers.size())
        return false;
    const RobustnessRequest& request = *s.robustness.state->request;
    try {
        SimulationRequest sim;
        sim.label = table->bodies[body] + " driven by " + table->controllers[controller];
        sim.experiment = request.experiment;
        sim.framed_body = std::make_shared<const evo::Body>(evo::robustness_cell_body(
            request.experiment, request.bodies[body], request.controllers[controller].entry));
        s.bodies.follow_champion = false;
        s.run.selected_id = -1;
        s.bodies.simulator.request(std::move(sim));
        s.robustness.shown_body = static_cast<int>(body);
        s.robustness.shown_controller = static_cast<int>(controller);
        set_status(s, "simulating " + table->bodies[body] + " driven by " +
                          table->controllers[controller]);
        return true;
    } catch (const std::exception& e) {
        set_status(s, e.what(), true);
        return false;
    }
}

namespace {

// One export of the finished table: `write` makes the file (atomically, naming the path when it
// fails), then the status names it.
template <class Write>
bool export_robustness(Studio& s, const std::string& path, const char* what, Write write) {
    const evo::RobustnessTable* table = robustness_table(s);
    if (!table) {
        set_status(s, "robustness: no finished table to export", true);
        return false;
    }
    try {
        make_parent(path);
        write(*table);
        set_status(s, std::string("robustness ") + what + " written: " + path);
        return true;
    } catch (const std::exception& e) {
        set_status(s, e.what(), true);
        return false;
    }
}

}  // namespace

bool export_robustness_csv(Studio& s, const std::string& path) {
    return export_robustness(s, path, "table", [&](const evo::RobustnessTable& table) {
        evo::write_file_atomically(path, evo::robustness_csv(table));
    });
}

bool export_robustness_png(Studio& s, const std::string& path) {
    return export_robustness(s, path, "heatmap", [&](const evo::RobustnessTable& table) {
        write_robustness_heatmap(path, table);  // throws naming the path (also without libpng)
    });
}

}  // namespace bhm::app::gui
