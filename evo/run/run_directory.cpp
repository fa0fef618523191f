#include "evo/run/run_directory.hpp"

#include <algorithm>
#include <charconv>
#include <filesystem>
#include <sstream>
#include <stdexcept>

#include <nlohmann/json.hpp>

#include "engine/io/text_file.hpp"
#include "evo/experiment/experiment_io.hpp"
#include "evo/experiment/json_fields.hpp"
#include "evo/run/checkpoint.hpp"
#include "evo/run/population_csv.hpp"
#include "evo/run/run_file_schema.hpp"

namespace bhm::evo {

namespace fs = std::filesystem;
using nlohmann::json;

namespace {

std::string path_in(const std::string& dir, const char* name) {
    return (fs::path(dir) / name).string();
}

std::string read_whole(const std::string& path, std::uint64_t cap) {
    try {
        return engine::read_text(path, cap);
    } catch (const engine::FileReadError& e) {
        throw std::runtime_error(
            e.what() + std::string(" (is this a run directory written by 'bhm evolve'?)"));
    }
}

json read_json_object(const std::string& path) {
    json j = json::parse(read_whole(path, engine::kTextFileCap), nullptr, false);
    if (j.is_discarded() || !j.is_object())
        throw std::runtime_error(path + ": not valid JSON (the file is damaged)");
    return j;
}

//! The file at context.path read by walking its field table: "PATH:field: message" on the first
//! field missing or wrong (the experiment and body readers name the file themselves).
template <class Rows, class Host>
void read_file(const Rows& fields, Host& host, RunFileContext& context) {
    const json j = read_json_object(context.path);
    try {
        read_fields(fields, Fields(j, ""), host, context);
    } catch (const FieldError& e) {
        throw std::runtime_error(context.path + ":" + e.what());
    }
}

}  // namespace

Experiment RunInfo::current() const {
    if (checkpoint_rules) return *checkpoint_rules;
    Experiment e = started;
    if (!rule_changes.empty()) e.fitness = rule_changes.back().fitness;
    // The physics of the last change that set it (a calibration applied to the live run).
    for (auto it = rule_changes.rbegin(); it != rule_changes.rend(); ++it) {
        if (!it->physics) continue;
        e = with_physics(e, *it->physics);
        break;
    }
    // The continuum checks' policy of the last change that set it.
    for (auto it = rule_changes.rbegin(); it != rule_changes.rend(); ++it) {
        if (!it->verify) continue;
        e.evolution.verify = *it->verify;
        break;
    }
    return e;
}

namespace {

void reconcile_with_checkpoint(const std::string& run_dir, const std::string& path, RunInfo& info) {
    const auto truth = read_checkpoint_rules(run_dir);
    if (!truth) return;
    if (truth->rule_changes != info.rule_changes || truth->experiment != info.current())
        info.warnings.push_back(path + ": its rules differ from the checkpoint's (" + truth->path +
                                ", checksummed); using the checkpoint's");
    info.rule_changes = truth->rule_changes;
    info.checkpoint_rules = truth->experiment;
}

}  // namespace

RunInfo read_run_info(const std::string& run_dir) {
    RunFileContext context;
    context.path = path_in(run_dir, kRunInfoFile);
    RunInfo info;
    read_file(run_info_fields(), info, context);
    reconcile_with_checkpoint(run_dir, context.path, info);
    return info;
}

namespace {

ChampionFile read_champion_at(const std::string& path, const std::string& run_dir,
                              const Experiment& experiment) {
    RunFileContext context{path, &experiment, run_dir};
    ChampionRecord champion;
    read_file(champion_file_fields(), champion, context);
    ChampionFile out;
    static_cast<MemberSummary&>(out) = summary_of(champion.individual);
    out.generation_found = champion.generation_found;
    out.body = std::move(champion.individual.phenotype.body);
    return out;
}

}  // namespace

ChampionSummary read_champion_summary(const std::string& path) {
    RunFileContext context;
    context.path = path;
    ChampionRecord champion;
    read_file(champion_file_fields(), champion, context);
    ChampionSummary out;
    static_cast<MemberSummary&>(out) = summary_of(champion.individual);
    out.generation_found = champion.generation_found;
    out.measure = context.measure;
    return out;
}

ChampionFile read_champion_file(const std::string& run_dir, const Experiment& experiment) {
    return read_champion_at(path_in(run_dir, kChampionFile), run_dir, experiment);
}

std::vector<ChampionFile> read_champion_history(const std::string& run_dir,
                                                const Experiment& experiment) {
    const std::filesystem::path dir = std::filesystem::path(run_dir) / kChampionsDir;
    std::vector<std::string> files;
    std::error_code error;
    for (const auto& entry : std::filesystem::directory_iterator(dir, error)) {
        const std::string name = entry.path().filename().string();
        if (name.rfind("gen-", 0) == 0 && entry.path().extension() == ".json")
            files.push_back(entry.path().string());
    }
    std::sort(files.begin(), files.end());  // gen-NNNNN: zero-padded, so oldest first
    std::vector<ChampionFile> out;
    for (const auto& file : files)
        out.push_back(read_champion_at(file, run_dir, experiment));
    if (out.empty()) out.push_back(read_champion_file(run_dir, experiment));
    return out;
}

std::size_t FitnessTable::column(const std::string& name) const {
    for (std::size_t i = 0; i < header.size(); ++i)
        if (header[i] == name) return i;
    throw std::runtime_error(path + ": no '" + name + "' column");
}

namespace {

FitnessTable read_numeric_csv(const std::string& path) {
    FitnessTable table;
    table.path = path;
    std::istringstream in(read_whole(table.path, engine::kLargeFileCap));
    std::string line;
    if (!std::getline(in, line) || line.empty())
        throw std::runtime_error(table.path + ": empty, no header");
    {
        std::istringstream h(line);
        std::string cell;
        while (std::getline(h, cell, ','))
            table.header.push_back(cell);
    }
    int row = 1;
    while (std::getline(in, line)) {
        ++row;
        if (line.empty()) continue;
        std::vector<double> values;
        std::istringstream r(line);
        std::string cell;
        bool numeric = true;
        while (std::getline(r, cell, ',')) {
            double v = 0.0;
            const auto [end, ec] = std::from_chars(cell.data(), cell.data() + cell.size(), v);
            numeric = numeric && ec == std::errc() && end == cell.data() + cell.size();
            values.push_back(v);
        }
        if (values.size() != table.header.size() || !numeric) {
            table.problem =
                table.path + ": row " + std::to_string(row) +
                (values.size() != table.header.size()
                     ? " has " + std::to_string(values.size()) + " cells, expected " +
                           std::to_string(table.header.size())
                     : std::string(" is not numeric")) +
                " (cut short by a crash or being written?); the rows before it are shown";
            break;
        }
        table.rows.push_back(std::move(values));
    }
    return table;
}

}  // namespace

FitnessTable read_fitness_table(const std::string& run_dir) {
    return read_numeric_csv(path_in(run_dir, kFitnessCsvFile));
}

FitnessTable read_population_table(const std::string& run_dir) {
    return read_numeric_csv(path_in(run_dir, kPopulationCsvFile));
}

}  // namespace bhm::evo
