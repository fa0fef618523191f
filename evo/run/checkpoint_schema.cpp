#include "evo/run/checkpoint_schema.hpp"

#include <array>
#include <vector>

#include "bhm_version.hpp"
#include "evo/experiment/experiment_io.hpp"
#include "evo/run/cache_entry_json.hpp"
#include "evo/run/checkpoint_parts.hpp"
#include "evo/run/loop_check_json.hpp"
#include "evo/run/rule_change_json.hpp"

namespace bhm::evo {

using nlohmann::json;

namespace {

using Context = CheckpointContext;
using Field = CheckpointFieldOf<RunState>;

constexpr const char* kFormat = "bhm-evolution-checkpoint";

// Formats: 1 the bare payload; 2 wrapped with its CRC-32 (behaviour descriptors came in 2);
// 3 NEAT's state (novelty search, early ends, physics changes and the continuum checks came in
// 3, each optional); 4 cache entries as named objects.

void write_format(const RunState&, const char* key, json& out, const Context&) {
    out[key] = kFormat;
}
void read_format(const Fields& f, const Field& field, RunState&, Context&) {
    if (f.string(field.key) != kFormat)
        f.fail(field.key, std::string("expected \"") + kFormat + "\"");
}

void write_version(const RunState&, const char* key, json& out, const Context&) {
    out[key] = kCheckpointFormatVersion;
}
//! The version the rows after it are read as.
void read_version(const Fields& f, const Field& field, RunState&, Context& context) {
    const auto version = f.integer(field.key);
    if (version < kOldestCheckpointFormatVersion || version > kCheckpointFormatVersion)
        f.fail(field.key, "unsupported version " + std::to_string(version) + " (this build reads " +
                              std::to_string(kOldestCheckpointFormatVersion) + " to " +
                              std::to_string(kCheckpointFormatVersion) + ")");
    context.version = static_cast<int>(version);
}

void write_bhm_version(const RunState&, const char* key, json& out, const Context&) {
    out[key] = BHM_VERSION_STRING;
}

void write_rng(const RunState& s, const char* key, json& out, const Context&) {
    json words = json::array();
    for (auto word : s.rng)
        words.push_back(hex64_text(word));
    out[key] = words;
}
void read_rng(const Fields& f, const Field& field, RunState& s, Context&) {
    const auto& rng = f.array(field.key);
    if (rng.size() != 4) f.fail(field.key, "expected 4 words");
    bool all_zero = true;
    for (std::size_t k = 0; k < 4; ++k) {
        const std::string where = item(f.join(field.key), k);
        if (!rng[k].is_string()) throw FieldError(where + ": expected a hex string");
        s.rng[k] = Fields::parse_hex(rng[k].get<std::string>(), where);
        all_zero = all_zero && s.rng[k] == 0;
    }
    if (all_zero) f.fail(field.key, "an all-zero state is not a valid xoshiro state");
}

void write_experiment(const RunState& s, const char* key, json& out, const Context&) {
    out[key] = experiment_to_json(s.experiment);
}
//! The rules in force, and what the rows after it read genomes with.
void read_experiment(const Fields& f, const Field& field, RunState& s, Context& context) {
    const json& experiment = f.at(field.key);
    try {
        s.experiment = parse_experiment(experiment, context.label + ":" + field.key);
    } catch (const std::exception& e) {
        throw FieldError(std::string(field.key) + ": " + e.what());
    }
    context.developer.emplace(s.experiment);
    context.weight_range = s.experiment.evolution.cppn.weight_range;
}

void write_population(const RunState& s, const char* key, json& out, const Context& context) {
    out[key] = write_objects<individual_fields>(s.population, context);
}
void read_population(const Fields& f, const Field& field, RunState& s, Context& context) {
    s.population =
        read_objects<individual_fields, Individual>(f.array(field.key), field.key, context);
    context.population = s.population.size();
    if (s.generation >= 0 &&
        static_cast<int>(s.population.size()) != s.experiment.evolution.population)
        f.fail(field.key, "size differs from evolution.population");
}

void write_pareto_rank(const RunState& s, const char* key, json& out, const Context&) {
    out[key] = s.pareto_rank;
}
void read_pareto_rank(const Fields& f, const Field& field, RunState& s, Context&) {
    const auto& ranks = f.array(field.key);
    if (ranks.size() != s.population.size())
        f.fail(field.key, "one rank per population member expected");
    for (const auto& r : ranks) {
        if (!r.is_number_integer()) f.fail(field.key, "expected integers");
        s.pareto_rank.push_back(r.get<int>());
    }
}

void write_history(const RunState& s, const char* key, json& out, const Context& context) {
    out[key] = write_objects<history_row_fields>(s.history, context);
}
void read_history(const Fields& f, const Field& field, RunState& s, Context& context) {
    s.history =
        read_objects<history_row_fields, HistoryRow>(f.array(field.key), field.key, context);
    if (static_cast<int>(s.history.size()) != s.generation + 1)
        f.fail(field.key, "expected one row per completed generation");
}

void write_rule_changes(const RunState& s, const char* key, json& out, const Context&) {
    out[key] = rule_changes_to_json(s.rule_changes, s.experiment);
}
void read_rule_changes(const Fields& f, const Field& field, RunState& s, Context&) {
    s.rule_changes = rule_changes_from_json(f.at(field.key), s.experiment, field.key);
}

void write_cache_capacity(const RunState& s, const char* key, json& out, const Context&) {
    out[key] = s.cache.capacity();
}
void read_cache_capacity(const Fields& f, const Field& field, RunState& s, Context&) {
    const auto capacity = f.integer(field.key);
    if (capacity < 0) f.fail(field.key, "must be >= 0");
    s.cache = FitnessCache(static_cast<std::size_t>(capacity));
}

void write_cache(const RunState& s, const char* key, json& out, const Context& context) {
    out[key] = cache_to_json(s.cache, context);
}
void read_cache_entries(const Fields& f, const Field& field, RunState& s, Context& context) {
    read_cache(f.array(field.key), field.key, s.experiment.fitness, context, s.cache);
}

bool neat(const RunState& s) {
    return uses_neat(s.experiment.evolution.algorithm);
}
void write_neat(const RunState& s, const char* key, json& out, const Context& context) {
    if (neat(s)) out[key] = write_fields(neat_state_fields(), s.neat, context);
}
//! NEAT runs past their first generation hold it (the population is read before it).
void read_neat(const Fields& f, const Field& field, RunState& s, Context& context) {
    if (!neat(s) || s.generation < 0) return;
    s.neat = read_part(neat_state_fields(), f.at(field.key), field.key, context);
}

bool novelty(const RunState& s) {
    return s.experiment.evolution.algorithm == Algorithm::Novelty;
}
void write_novelty_archive(const RunState& s, const char* key, json& out, const Context& context) {
    if (novelty(s)) out[key] = write_fields(novelty_archive_fields(), s.novelty_archive, context);
}
void read_novelty_archive(const Fields& f, const Field& field, RunState& s, Context& context) {
    if (!novelty(s) || s.generation < 0) return;
    s.novelty_archive = read_part(novelty_archive_fields(), f.at(field.key), field.key, context);
}

void write_pending_checks(const RunState& s, const char* key, json& out, const Context&) {
    if (s.pending_checks) out[key] = pending_checks_to_json(*s.pending_checks);
}
void read_pending_checks(const Fields& f, const Field& field, RunState& s, Context& context) {
    if (field.skipped(f, context)) return;
    s.pending_checks = pending_checks_from_json(f.at(field.key), field.key);
}

void write_loop_checks(const RunState& s, const char* key, json& out, const Context&) {
    if (s.loop_checks.empty()) return;
    json checks = json::array();
    for (const auto& c : s.loop_checks)
        checks.push_back(loop_check_to_json(c));
    out[key] = checks;
}
void read_loop_checks(const Fields& f, const Field& field, RunState& s, Context& context) {
    if (field.skipped(f, context)) return;
    const auto& checks = f.array(field.key);
    for (std::size_t i = 0; i < checks.size(); ++i)
        s.loop_checks.push_back(loop_check_from_json(checks[i], item(field.key, i)));
}

void write_champion(const RunState& s, const char* key, json& out, const Context& context) {
    out[key] = s.champion ? write_fields(champion_fields(), *s.champion, context) : json(nullptr);
}
void read_champion(const Fields& f, const Field& field, RunState& s, Context& context) {
    if (f.at(field.key).is_null()) return;
    s.champion = read_part(champion_fields(), f.at(field.key), field.key, context);
}
//! Its rows hold only where it is not null.
void describe_champion(const SchemaLine& self, std::vector<SchemaLine>& out) {
    SchemaLine parent = self;
    parent.when = "champion not null";
    describe_fields(champion_fields(), self.path + ".", &parent, out);
}

constexpr const char* kNeatRuns = "NEAT runs";
constexpr const char* kNoveltyRuns = "novelty search runs";
constexpr const char* kChecking = "runs with continuum checks";

// In the order they are read: each row may use what the rows before it read (the version, the
// experiment's developer, the generation, the population, the cache's capacity).
constexpr std::array kRunState = {
    Field{"format", "string", 1, "", "always `bhm-evolution-checkpoint`", write_format,
          read_format},
    Field{"format_version", "integer", 1, "",
          "this file's format: it says which form the cache holds", write_version, read_version},
    Field{"bhm_version", "string", 1, "", "the bhm that wrote it (not read back)",
          write_bhm_version, nullptr},
    hex_field<&RunState::seed, Context>("seed", 1, "", "the run's seed"),
    member_field<&RunState::generation, Context>("generation", 1, "",
                                                 "the last completed generation (-1: none)"),
    member_field<&RunState::next_id, Context>("next_id", 1, "",
                                              "the id the next new individual gets"),
    Field{"rng", "array", 1, "", "the xoshiro256** state: 4 hex words, not all zero", write_rng,
          read_rng},
    member_field<&RunState::rules_version, Context>("rules_version", 1, "",
                                                    "bumped by every rule change"),
    member_field<&RunState::elapsed_s, Context>(
        "elapsed_s", 1, "",
        "wall time of the completed generations, across resumes (paused time excluded)"),
    Field{"experiment", "experiment", 1, "",
          "the rules in force, as the experiment file writes them: the fitness of the last "
          "change, the physics of the last physics change",
          write_experiment, read_experiment},
    Field{"population", "objects", 1, "",
          "the members in selection order; each phenotype is developed again on load and checked "
          "against its hash",
          write_population, read_population, describe_object<individual_fields>},
    Field{"pareto_rank", "array", 1, "", "per member, from the last selection", write_pareto_rank,
          read_pareto_rank},
    Field{"history", "objects", 1, "", "one row per completed generation (fitness.csv's rows)",
          write_history, read_history, describe_object<history_row_fields>},
    Field{"rule_changes", "objects", 1, "",
          "every rule change in order, the form run.json's holds too "
          "(evo/run/rule_change_json.hpp)",
          write_rule_changes, read_rule_changes, describe_object<rule_change_fields>},
    Field{"cache_capacity", "integer", 1, "", "the fitness cache's size limit",
          write_cache_capacity, read_cache_capacity},
    Field{"cache", "objects", 1, "",
          "the fitness cache, oldest first; formats 1 to 3 hold positional arrays "
          "(evo/run/cache_entry_json.hpp)",
          write_cache, read_cache_entries, describe_object<cache_entry_fields>},
    Field{"neat", "object", 3, kNeatRuns, "innovation counters and species", write_neat, read_neat,
          describe_object<neat_state_fields>},
    Field{"novelty_archive", "object", 3, kNoveltyRuns, "the archive", write_novelty_archive,
          read_novelty_archive, describe_object<novelty_archive_fields>},
    Field{"pending_checks", "pending checks", 3, kChecking,
          "bodies picked for checking whose results land later", write_pending_checks,
          read_pending_checks},
    Field{"loop_checks", "array", 3, kChecking,
          "every check applied so far (evo/run/loop_check_json.hpp); each check's `laws`, the "
          "continuum laws solved (the judged one first), is absent in checkpoints written before "
          "it and then read as none",
          write_loop_checks, read_loop_checks},
    Field{"champion", "object or null", 1, "", "the best individual so far", write_champion,
          read_champion, describe_champion},
};

std::vector<SchemaLine> all_lines() {
    std::vector<SchemaLine> lines;
    describe_fields(kRunState, "", nullptr, lines);
    return lines;
}

}  // namespace

std::span<const Field> run_state_fields() {
    return kRunState;
}

std::span<const CheckpointField> checkpoint_fields() {
    static const std::vector<SchemaLine> lines = all_lines();
    return lines;
}

const CheckpointField* find_checkpoint_field(std::string_view path) {
    return find_schema_line(checkpoint_fields(), path);
}

std::string checkpoint_schema_markdown() {
    return schema_markdown(checkpoint_fields());
}

}  // namespace bhm::evo
