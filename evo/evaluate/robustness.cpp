// Robustness tables: controllers resolved, cells evaluated, CSV written and read (robustness.hpp).
#include "evo/evaluate/robustness.hpp"

#include <atomic>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <sstream>
#include <stdexcept>

#include <nlohmann/json.hpp>

#include "engine/io/text_file.hpp"
#include "evo/evaluate/worker_pool.hpp"
#include "evo/experiment/body_spec_of.hpp"
#include "evo/experiment/json_reader.hpp"
#include "evo/genome/controller.hpp"

namespace bhm::evo {

namespace {

std::string csv_field(const std::string& text) {
    if (text.find_first_of(",\"\r\n") == std::string::npos) return text;
    std::string out = "\"";
    for (const char c : text) {
        if (c == '"') out += '"';
        out += c;
    }
    return out + "\"";
}

// One CSV record from text at pos (RFC 4180 quoting, fields may hold line breaks); pos moves past
// its line break.
std::vector<std::string> csv_record(const std::string& text, std::size_t& pos, int line) {
    std::vector<std::string> fields(1);
    bool quoted = false;
    while (pos < text.size()) {
        const char c = text[pos++];
        if (quoted) {
            if (c != '"') {
                fields.back() += c;
            } else if (pos < text.size() && text[pos] == '"') {
                fields.back() += '"';
                ++pos;
            } else {
                quoted = false;
            }
        } else if (c == '"') {
            quoted = true;
        } else if (c == ',') {
            fields.emplace_back();
        } else if (c == '\n') {
            return fields;
        } else if (c != '\r') {
            fields.back() += c;
        }
    }
    if (quoted)
        throw std::invalid_argument("robustness.csv line " + std::to_string(line) +
                                    ": a quoted field is not closed");
    return fields;
}

}  // namespace

RobustnessController resolve_robustness_controller(const std::string& item, double weight_range) {
    RobustnessController out;
    out.label = item;
    if (item.empty())
        throw std::invalid_argument("an empty controller name (two commas, or one at an end)");
    if (item == "uniform" || item == "wave" || item == "random") {
        out.entry.name = item;
        return out;
    }
    if (item.rfind("random:", 0) == 0) {
        const std::string digits = item.substr(7);
        if (digits.empty() || digits.size() > 15 ||
            digits.find_first_not_of("0123456789") != std::string::npos)
            throw std::invalid_argument(item +
                                        ": the seed of random:SEED must be an integer in "
                                        "[0, 999999999999999]");
        out.entry.name = "random";
        out.entry.seed = std::stoull(digits);
        return out;
    }
    namespace fs = std::filesystem;
    std::error_code ec;
    fs::path file = item;
    if (fs::is_directory(file, ec)) {
        file /= kControllerFile;
        if (!fs::exists(file, ec))
            throw std::invalid_argument(
                file.string() +
                ": missing (a run writes controller.json only when its champion has a controller: "
                "evolution.controller mode coevolve or fixed_body)");
    } else if (!fs::exists(file, ec)) {
        throw std::invalid_argument(item +
                                    ": neither a built-in controller (uniform, random, "
                                    "random:SEED, wave) nor an existing controller file or run "
                                    "directory");
    }
    nlohmann::json json;
    try {
        json = nlohmann::json::parse(engine::read_text(file.string(), engine::kTextFileCap));
    } catch (const std::exception& e) {
        throw std::invalid_argument(file.string() +
                                    ": not a controller file: " + without_json_tags(e.what()));
    }
    try {
        (void)controller_program_from_json(json,
                                           weight_range);  // checked now, painted per cell later
    } catch (const std::exception& e) {
        throw std::invalid_argument(file.string() + ": " + without_json_tags(e.what()));
    }
    out.entry.name = item;
    out.entry.genome_json = json.dump();
    return out;
}

Body robustness_cell_body(const Experiment& experiment, const Body& body,
                          const ControllerEntry& controller) {
    Body framed = apply_frame_and_overrides(experiment, body);
    paint_controller_entry(controller, experiment.evolution.cppn.weight_range, experiment.materials,
                           framed);
    return framed;
}

RobustnessTable evaluate_robustness(const Experiment& experiment, const std::vector<Body>& bodies,
                                    const std::vector<std::string>& body_labels,
                                    const std::vector<RobustnessController>& controllers,
                                    int threads, const std::function<void(int, int)>& on_cell,
                                    const std::atomic<bool>* cancel) {
    if (body_labels.size() != bodies.size())
        throw std::invalid_argument("evaluate_robustness: one label per body");
    RobustnessTable table;
    table.bodies = body_labels;
    for (const auto& c : controllers)
        table.controllers.push_back(c.label);
    const int cols = static_cast<int>(controllers.size());
    const int total = static_cast<int>(bodies.size()) * cols;
    table.fitness.assign(static_cast<std::size_t>(total), 0.0);
    table.reports.assign(static_cast<std::size_t>(total), FitnessReport{});
    std::atomic<int> done{0};
    parallel_for(total, resolve_thread_count(threads), [&](int cell) {
        const auto k = static_cast<std::size_t>(cell);
        const Body painted = robustness_cell_body(experiment, bodies[k / controllers.size()],
                                                  controllers[k % controllers.size()].entry);
        table.reports[k] = evaluate_body(experiment, painted, cancel);
        table.fitness[k] = fitness_under(table.reports[k], experiment.fitness);
        const int finished = ++done;
        if (on_cell) on_cell(finished, total);
    });
    return table;
}

std::string robustness_csv(const RobustnessTable& table) {
    std::string out = "body";
    for (const auto& c : table.controllers)
        out += "," + csv_field(c);
    out += "\n";
    char number[40];
    for (std::size_t b = 0; b < table.bodies.size(); ++b) {
        out += csv_field(table.bodies[b]);
        for (std::size_t c = 0; c < table.controllers.size(); ++c) {
            std::snprintf(number, sizeof number, "%.17g", table.at(b, c));
            out += ",";
            out += number;
        }
        out += "\n";
    }
    return out;
}

RobustnessTable parse_robustness_csv(const std::string& text) {
    RobustnessTable table;
    std::size_t pos = 0;
    int line = 1;
    const auto header = csv_record(text, pos, line);
    if (header.empty() || header[0] != "body")
        throw std::invalid_argument("robustness.csv line 1: expected a header starting \"body\"");
    table.controllers.assign(header.begin() + 1, header.end());
    while (pos < text.size()) {
        ++line;
        const auto row = csv_record(text, pos, line);
        if (row.size() == 1 && row[0].empty()) continue;  // a blank line
        if (row.size() != header.size())
            throw std::invalid_argument("robustness.csv line " + std::to_string(line) + ": " +
                                        std::to_string(row.size()) + " fields, expected " +
                                        std::to_string(header.size()));
        table.bodies.push_back(row[0]);
        for (std::size_t c = 1; c < row.size(); ++c) {
            std::size_t used = 0;
            double value = 0.0;
            try {
                value = std::stod(row[c], &used);
            } catch (const std::exception&) {
                used = 0;
            }
            if (used == 0 || used != row[c].size())
                throw std::invalid_argument("robustness.csv line " + std::to_string(line) +
                                            ", column " + csv_field(header[c]) +
                                            ": not a number: \"" + row[c] + "\"");
            table.fitness.push_back(value);
        }
    }
    return table;
}

}  // namespace bhm::evo
