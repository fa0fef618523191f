#include "app/cli/run_directory.hpp"

#include <filesystem>
#include <fstream>
#include <stdexcept>

#include <nlohmann/json.hpp>

#include "engine/io/text_file.hpp"
#include "evo/experiment/experiment_io.hpp"

namespace bhm::app {

namespace {

nlohmann::json read_json(const std::string& path) {
    std::string text;
    try {
        text = engine::read_text(path, engine::kTextFileCap);
    } catch (const engine::FileReadError& e) {
        throw std::runtime_error(
            e.what() + std::string(" (is this a run directory written by 'bhm evolve'?)"));
    }
    auto json = nlohmann::json::parse(text, nullptr, false);
    if (json.is_discarded() || !json.is_object())
        throw std::runtime_error(path + ": not valid JSON (the file is damaged)");
    return json;
}

}  // namespace

RunChampion load_run_champion(const std::string& run_dir) {
    namespace fs = std::filesystem;
    const std::string run_path = (fs::path(run_dir) / "run.json").string();
    const std::string champion_path = (fs::path(run_dir) / "champion.json").string();
    RunChampion out;
    auto run = read_json(run_path);
    if (!run.contains("experiment")) throw std::runtime_error(run_path + ":experiment: missing");
    out.experiment = evo::parse_experiment(run["experiment"], run_path + " (experiment)");
    // Rule changes made during the run (studio: expert in the loop) replace the fitness section;
    // the champion was judged under the last of them.
    if (auto changes = run.find("rule_changes");
        changes != run.end() && changes->is_array() && !changes->empty()) {
        auto j = evo::experiment_to_json(out.experiment);
        j["fitness"] = changes->back().at("fitness");
        out.experiment = evo::parse_experiment(j, run_path + " (rule_changes)");
    }
    auto champion = read_json(champion_path);
    if (!champion.contains("phenotype"))
        throw std::runtime_error(champion_path + ":phenotype: missing");
    out.body = evo::parse_body(champion["phenotype"], champion_path + " (phenotype)");
    // A champion from another experiment (files mixed up, a damaged run.json) would export
    // materials and cells that experiment does not define: refuse it, naming both files.
    const auto problems =
        evo::validate_body_against(out.body, out.experiment, champion_path + " (phenotype)");
    if (!problems.empty())
        throw std::runtime_error(problems.front().to_string() + " (the champion does not fit " +
                                 run_path + "'s experiment)");
    out.fitness = champion.value("fitness", 0.0);
    out.generation = champion.value("generation_found", 0);
    return out;
}

}  // namespace bhm::app
