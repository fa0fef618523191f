#include "evo/run/checkpoint.hpp"

#include <cinttypes>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <stdexcept>
#include <string_view>

#include "bhm_version.hpp"
#include "engine/io/atomic_file.hpp"
#include "engine/io/text_file.hpp"
#include "evo/evaluate/behaviour.hpp"
#include "evo/evaluate/fitness_json.hpp"
#include "evo/experiment/experiment_io.hpp"
#include "evo/experiment/json_fields.hpp"
#include "evo/experiment/json_reader.hpp"
#include "evo/genome/phenotype.hpp"
#include "evo/run/crc32.hpp"
#include "evo/run/loop_check_json.hpp"
#include "evo/run/rule_change_json.hpp"

namespace bhm::evo {

using nlohmann::json;
namespace fs = std::filesystem;

namespace {

constexpr const char* kFormat = "bhm-evolution-checkpoint";
constexpr int kFormatVersion = kCheckpointFormatVersion;
constexpr int kOldestReadableVersion = kOldestCheckpointFormatVersion;
constexpr std::string_view kChecksumPrefix = "{\"checksum\":\"crc32:";
constexpr std::string_view kPayloadPrefix = "\",\"payload\":";
constexpr std::string_view kClosing = "}\n";

std::string hex(std::uint64_t v) {
    char buffer[24];
    std::snprintf(buffer, sizeof buffer, "%016" PRIx64, v);
    return buffer;
}

Individual individual_from_json(const json& j, const std::string& path, const Developer& developer,
                                double weight_range) {
    const Fields f(j, path);
    Individual ind;
    ind.id = f.integer("id");
    ind.parent_id = f.integer("parent_id");
    ind.age = static_cast<int>(f.integer("age"));
    ind.born_generation = static_cast<int>(f.integer("born_generation"));
    ind.evaluated = f.boolean("evaluated");
    ind.valid = f.boolean("valid");
    try {
        ind.genome = genome_from_json(f.at("genome"), weight_range);
    } catch (const std::invalid_argument& e) {
        throw FieldError(path + "." + e.what());
    }
    ind.phenotype = developer.develop(ind.genome);
    if (ind.phenotype.hash != f.hex64("phenotype_hash"))
        f.fail("phenotype_hash",
               "the genome develops into a different body (decoder or experiment changed?)");
    ind.report = report_from_json(f.at("report"), f.join("report"));
    return ind;
}

json history_row_to_json(const HistoryRow& h) {
    json j = {{"generation", h.generation},
              {"evaluations", h.evaluations},
              {"simulations", h.simulations},
              {"best_fitness", h.best_fitness},
              {"median_fitness", h.median_fitness},
              {"best_age", h.best_age},
              {"best_id", h.best_id},
              {"diverged", h.diverged},
              {"wall_s", h.wall_s},
              {"rules_version", h.rules_version},
              {"best_exploits", exploits_to_json(h.best_exploits)},
              {"flagged_members", h.flagged_members},
              {"species", h.species},
              {"ended_early", h.ended_early},
              {"mean_simulated_s", h.mean_simulated_s},
              {"best_simulated_s", h.best_simulated_s},
              {"best_periodic_residual", h.best_periodic_residual}};
    if (h.novelty) {
        const auto& n = *h.novelty;
        j["novelty"] = {{"best_novelty", n.best_novelty},
                        {"median_novelty", n.median_novelty},
                        {"archive_size", n.archive_size},
                        {"archive_added", n.archive_added},
                        {"archive_threshold", n.archive_threshold},
                        {"champion_fitness", n.champion_fitness}};
    }
    if (h.verify) j["verify"] = loop_check_row_to_json(*h.verify);
    return j;
}

HistoryRow history_row_from_json(const json& j, const std::string& path) {
    const Fields f(j, path);
    HistoryRow h;
    h.generation = static_cast<int>(f.integer("generation"));
    h.evaluations = static_cast<int>(f.integer("evaluations"));
    h.simulations = static_cast<int>(f.integer("simulations"));
    h.best_fitness = f.number("best_fitness");
    h.median_fitness = f.number("median_fitness");
    h.best_age = static_cast<int>(f.integer("best_age"));
    h.best_id = f.integer("best_id");
    h.diverged = static_cast<int>(f.integer("diverged"));
    h.wall_s = f.number("wall_s");
    h.rules_version = static_cast<int>(f.integer("rules_version"));
    // Both absent in checkpoints written before exploit detection.
    if (j.contains("best_exploits")) {
        try {
            h.best_exploits = exploits_from_json(j.at("best_exploits"));
        } catch (const std::invalid_argument& e) {
            throw FieldError(path + "." + e.what());
        }
    }
    if (j.contains("flagged_members"))
        h.flagged_members = static_cast<int>(f.integer("flagged_members"));
    if (j.contains("species")) h.species = static_cast<int>(f.integer("species"));  // format 3
    // Absent before evaluations could end early: every simulation then ran the full time.
    if (j.contains("ended_early")) h.ended_early = static_cast<int>(f.integer("ended_early"));
    if (j.contains("mean_simulated_s")) h.mean_simulated_s = f.number("mean_simulated_s");
    if (j.contains("best_simulated_s")) h.best_simulated_s = f.number("best_simulated_s");
    if (j.contains("best_periodic_residual"))
        h.best_periodic_residual = f.number("best_periodic_residual");
    if (j.contains("novelty")) {  // novelty search runs only
        const Fields n(j.at("novelty"), f.join("novelty"));
        NoveltyRow row;
        row.best_novelty = n.number("best_novelty");
        row.median_novelty = n.number("median_novelty");
        row.archive_size = static_cast<int>(n.integer("archive_size"));
        row.archive_added = static_cast<int>(n.integer("archive_added"));
        row.archive_threshold = n.number("archive_threshold");
        row.champion_fitness = n.number("champion_fitness");
        h.novelty = row;
    }
    if (j.contains("verify"))  // runs with checks in the loop only
        h.verify = loop_check_row_from_json(j.at("verify"), f.join("verify"));
    return h;
}

json novelty_archive_to_json(const NoveltyArchive& a) {
    return {{"threshold", a.threshold}, {"entries", a.entries}};
}

NoveltyArchive novelty_archive_from_json(const json& j) {
    const Fields f(j, "novelty_archive");
    NoveltyArchive a;
    a.threshold = f.number("threshold");
    if (!(a.threshold > 0.0)) f.fail("threshold", "must be > 0");
    const auto& entries = f.array("entries");
    for (std::size_t i = 0; i < entries.size(); ++i) {
        auto entry = behaviour_from_json(entries[i], item("novelty_archive.entries", i));
        if (entry.empty()) f.fail("entries", "an archive entry is a whole descriptor");
        a.entries.push_back(std::move(entry));
    }
    return a;
}

json neat_state_to_json(const NeatState& n) {
    json species = json::array();
    for (const auto& s : n.species)
        species.push_back({{"id", s.id},
                           {"representative", genome_to_json(s.representative)},
                           {"best_fitness", s.best_fitness},
                           {"last_improved", s.last_improved},
                           {"created", s.created},
                           {"members", s.members}});
    return {{"next_innovation", n.next_innovation},
            {"next_node_id", n.next_node_id},
            {"next_species_id", n.next_species_id},
            {"threshold", n.threshold},
            {"species", species}};
}

NeatState neat_state_from_json(const json& j, double weight_range, std::size_t population) {
    const Fields f(j, "neat");
    NeatState n;
    n.next_innovation = f.integer("next_innovation");
    n.next_node_id = f.integer("next_node_id");
    n.next_species_id = static_cast<int>(f.integer("next_species_id"));
    n.threshold = f.number("threshold");
    const auto& species = f.array("species");
    std::size_t members = 0;
    for (std::size_t i = 0; i < species.size(); ++i) {
        const Fields s(species[i], item("neat.species", i));
        NeatSpecies sp;
        sp.id = static_cast<int>(s.integer("id"));
        try {
            sp.representative = genome_from_json(s.at("representative"), weight_range);
        } catch (const std::invalid_argument& e) {
            throw FieldError(s.join("representative") + ": " + e.what());
        }
        // -inf cannot be stored in JSON (it is written as null): a species always has a best.
        sp.best_fitness = s.number("best_fitness");
        sp.last_improved = static_cast<int>(s.integer("last_improved"));
        sp.created = static_cast<int>(s.integer("created"));
        for (const auto& m : s.array("members")) {
            if (!m.is_number_integer() || m.get<std::int64_t>() < 0 ||
                m.get<std::size_t>() >= population)
                s.fail("members", "expected indices into the population");
            sp.members.push_back(m.get<int>());
        }
        if (sp.members.empty()) s.fail("members", "a species has at least one member");
        members += sp.members.size();
        n.species.push_back(std::move(sp));
    }
    if (members != population) f.fail("species", "every population member in one species expected");
    return n;
}

//! A cache entry (format 4 on): {"hash": phenotype hash, "report": the FitnessReport in its one
//! form, fitness_json.hpp}, the report exactly as simulated.
json cache_entry_to_json(std::uint64_t hash, const FitnessReport& report) {
    return {{"hash", hex(hash)}, {"report", report_to_json(report)}};
}

std::pair<std::uint64_t, FitnessReport> cache_entry_from_json(const json& j,
                                                              const std::string& where) {
    if (j.is_array())
        throw FieldError(where + ": a positional entry in a format " +
                         std::to_string(kNamedCacheEntriesSince) +
                         " checkpoint (expected {hash, report})");
    const Fields f(j, where);
    return {f.hex64("hash"), report_from_json(f.at("report"), f.join("report"))};
}

//! Formats 1 to 3: [hash, diverged, steps, simulated_s, measures, divergence_reason, exploits,
//! behaviour, {ended_early, periodic_residual}]. The 7th element (exploit flags) came with
//! exploit detection, the 8th (the behaviour descriptor) with behaviour descriptors, the 9th with
//! evaluations that end when the motion repeats: older checkpoints have 6 to 8. The form held
//! neither the fitness (scored here under `rules`) nor sim_wall_s (0).
std::pair<std::uint64_t, FitnessReport> positional_cache_entry_from_json(const json& e,
                                                                         const std::string& where,
                                                                         const Fitness& rules) {
    if (!e.is_array() || e.size() < 6 || e.size() > 9)
        throw FieldError(where +
                         ": expected [hash, diverged, steps, simulated_s, measures, reason, "
                         "exploits, behaviour, early end] (formats 1 to 3)");
    auto element = [&](std::size_t k, const char* name) {
        return item(where, k) + " (" + name + ")";
    };
    auto need = [&](bool ok, std::size_t k, const char* name, const char* expected) {
        if (!ok) throw FieldError(element(k, name) + ": expected " + expected);
    };
    need(e[0].is_string(), 0, "hash", "a hex string");
    need(e[1].is_boolean(), 1, "diverged", "true or false");
    need(e[2].is_number_integer(), 2, "steps", "an integer");
    need(e[3].is_number(), 3, "simulated_s", "a number");
    need(e[4].is_array() && e[4].size() == static_cast<std::size_t>(kMeasureCount), 4, "measures",
         "an array of one number per measure");
    need(e[5].is_string(), 5, "divergence_reason", "a string");
    FitnessReport r;
    r.diverged = e[1].get<bool>();
    r.steps = e[2].get<std::int64_t>();
    r.simulated_s = e[3].get<double>();
    for (std::size_t k = 0; k < r.measures.size(); ++k) {
        need(e[4][k].is_number(), 4, "measures", "numbers");
        r.measures[k] = e[4][k].get<double>();
    }
    r.divergence_reason = e[5].get<std::string>();
    if (e.size() >= 7) {
        try {
            r.exploits = exploits_from_json(e[6]);
        } catch (const std::invalid_argument& ex) {
            throw FieldError(item(where, 6) + "." + ex.what());
        }
    }
    if (e.size() >= 8) r.behaviour = behaviour_from_json(e[7], element(7, "behaviour"));
    if (e.size() == 9) {
        const Fields early(e[8], item(where, 8));
        r.ended_early = early.boolean("ended_early");
        r.periodic_residual = early.number("periodic_residual");
    }
    r.fitness = fitness_under(r, rules);
    return {Fields::parse_hex(e[0].get<std::string>(), element(0, "hash")), r};
}

}  // namespace

json individual_to_json(const Individual& ind) {
    return {{"id", ind.id},
            {"parent_id", ind.parent_id},
            {"age", ind.age},
            {"born_generation", ind.born_generation},
            {"evaluated", ind.evaluated},
            {"valid", ind.valid},
            {"phenotype_hash", hex(ind.phenotype.hash)},
            {"genome", genome_to_json(ind.genome)},
            {"report", report_to_json(ind.report)}};
}

json run_state_to_json(const RunState& s) {
    json population = json::array();
    for (const auto& ind : s.population)
        population.push_back(individual_to_json(ind));
    json history = json::array();
    for (const auto& h : s.history)
        history.push_back(history_row_to_json(h));
    json cache = json::array();
    for (const auto hash : s.cache.insertion_order())
        cache.push_back(cache_entry_to_json(hash, *s.cache.find(hash)));
    json rng = json::array();
    for (auto word : s.rng)
        rng.push_back(hex(word));
    json j = {{"format", kFormat},
              {"format_version", kFormatVersion},
              {"bhm_version", BHM_VERSION_STRING},
              {"seed", hex(s.seed)},
              {"generation", s.generation},
              {"next_id", s.next_id},
              {"rng", rng},
              {"rules_version", s.rules_version},
              {"elapsed_s", s.elapsed_s},
              {"experiment", experiment_to_json(s.experiment)},
              {"population", population},
              {"pareto_rank", s.pareto_rank},
              {"history", history},
              {"rule_changes", rule_changes_to_json(s.rule_changes, s.experiment)},
              {"cache_capacity", s.cache.capacity()},
              {"cache", cache}};
    if (s.experiment.evolution.algorithm == Algorithm::Neat) j["neat"] = neat_state_to_json(s.neat);
    if (s.experiment.evolution.algorithm == Algorithm::Novelty)
        j["novelty_archive"] = novelty_archive_to_json(s.novelty_archive);
    if (s.pending_checks) j["pending_checks"] = pending_checks_to_json(*s.pending_checks);
    if (!s.loop_checks.empty()) {
        json checks = json::array();
        for (const auto& c : s.loop_checks)
            checks.push_back(loop_check_to_json(c));
        j["loop_checks"] = checks;
    }
    j["champion"] = s.champion ? json{{"generation_found", s.champion->generation_found},
                                      {"individual", individual_to_json(s.champion->individual)}}
                               : json(nullptr);
    return j;
}

RunState run_state_from_json(const json& j, const std::string& label) {
    try {
        const Fields f(j, "");
        if (f.string("format") != kFormat)
            f.fail("format", std::string("expected \"") + kFormat + "\"");
        const auto version = f.integer("format_version");
        if (version < kOldestReadableVersion || version > kFormatVersion)
            f.fail("format_version", "unsupported version " + std::to_string(version) +
                                         " (this build reads " +
                                         std::to_string(kOldestReadableVersion) + " to " +
                                         std::to_string(kFormatVersion) + ")");
        RunState s;
        try {
            s.experiment = parse_experiment(f.at("experiment"), label + ":experiment");
        } catch (const std::exception& e) {
            throw FieldError(std::string("experiment: ") + e.what());
        }
        s.seed = f.hex64("seed");
        s.generation = static_cast<int>(f.integer("generation"));
        s.next_id = f.integer("next_id");
        const auto& rng = f.array("rng");
        if (rng.size() != 4) f.fail("rng", "expected 4 words");
        bool all_zero = true;
        for (std::size_t k = 0; k < 4; ++k) {
            if (!rng[k].is_string()) throw FieldError(item("rng", k) + ": expected a hex string");
            s.rng[k] = Fields::parse_hex(rng[k].get<std::string>(), item("rng", k));
            all_zero = all_zero && s.rng[k] == 0;
        }
        if (all_zero) f.fail("rng", "an all-zero state is not a valid xoshiro state");
        s.rules_version = static_cast<int>(f.integer("rules_version"));
        s.elapsed_s = f.number("elapsed_s");

        const Developer developer(s.experiment);
        const double range = s.experiment.evolution.cppn.weight_range;
        const auto& population = f.array("population");
        for (std::size_t i = 0; i < population.size(); ++i)
            s.population.push_back(
                individual_from_json(population[i], item("population", i), developer, range));
        const auto& ranks = f.array("pareto_rank");
        if (ranks.size() != s.population.size())
            f.fail("pareto_rank", "one rank per population member expected");
        for (const auto& r : ranks) {
            if (!r.is_number_integer()) f.fail("pareto_rank", "expected integers");
            s.pareto_rank.push_back(r.get<int>());
        }
        if (s.generation >= 0 &&
            static_cast<int>(s.population.size()) != s.experiment.evolution.population)
            f.fail("population", "size differs from evolution.population");

        const auto& history = f.array("history");
        for (std::size_t i = 0; i < history.size(); ++i)
            s.history.push_back(history_row_from_json(history[i], item("history", i)));
        if (static_cast<int>(s.history.size()) != s.generation + 1)
            f.fail("history", "expected one row per completed generation");

        s.rule_changes = rule_changes_from_json(f.at("rule_changes"), s.experiment, "rule_changes");

        if (s.experiment.evolution.algorithm == Algorithm::Neat && s.generation >= 0)
            s.neat = neat_state_from_json(f.at("neat"), range, s.population.size());
        if (s.experiment.evolution.algorithm == Algorithm::Novelty && s.generation >= 0)
            s.novelty_archive = novelty_archive_from_json(f.at("novelty_archive"));
        if (j.contains("pending_checks"))
            s.pending_checks = pending_checks_from_json(f.at("pending_checks"), "pending_checks");
        if (j.contains("loop_checks")) {  // runs with continuum checks in the loop only
            const auto& checks = f.array("loop_checks");
            for (std::size_t i = 0; i < checks.size(); ++i)
                s.loop_checks.push_back(loop_check_from_json(checks[i], item("loop_checks", i)));
        }

        if (!f.at("champion").is_null()) {
            const Fields c(f.at("champion"), "champion");
            s.champion = ChampionRecord{
                individual_from_json(c.at("individual"), "champion.individual", developer, range),
                static_cast<int>(c.integer("generation_found"))};
        }

        const auto capacity = f.integer("cache_capacity");
        if (capacity < 0) f.fail("cache_capacity", "must be >= 0");
        s.cache = FitnessCache(static_cast<std::size_t>(capacity));
        const auto& cache = f.array("cache");
        for (std::size_t i = 0; i < cache.size(); ++i) {
            auto [hash, report] = version >= kNamedCacheEntriesSince
                                      ? cache_entry_from_json(cache[i], item("cache", i))
                                      : positional_cache_entry_from_json(cache[i], item("cache", i),
                                                                         s.experiment.fitness);
            s.cache.insert(hash, report);
        }
        return s;
    } catch (const FieldError& e) {
        throw std::runtime_error(label + ": " + e.what());
    } catch (const json::exception& e) {
        throw std::runtime_error(label + ": " + without_json_tags(e.what()));
    }
}

std::string checkpoint_text(const json& payload) {
    const std::string body = payload.dump(1);
    char crc[9];
    std::snprintf(crc, sizeof crc, "%08" PRIx32, crc32(body));
    return std::string(kChecksumPrefix) + crc + std::string(kPayloadPrefix) + body +
           std::string(kClosing);
}

json parse_checkpoint_text(const std::string& text, std::vector<std::string>& notes) {
    const std::string_view all(text);
    if (all.substr(0, kChecksumPrefix.size()) != kChecksumPrefix) {
        // Format 1 (no checksum) or damage to the very first bytes.
        json j;
        try {
            j = json::parse(text);
        } catch (const json::parse_error& e) {
            // Its own words without nlohmann's tags: this reaches the resume warning (issue 41 R9).
            throw std::runtime_error(std::string("not a checkpoint: no checksum header and not "
                                                 "valid JSON (") +
                                     without_json_tags(e.what()) + ")");
        }
        if (!j.is_object() || j.value("format_version", 0) != 1)
            throw std::runtime_error("damaged: the checksum header is missing");
        notes.push_back("format 1 carries no checksum: its contents are not verified");
        return j;
    }
    const std::size_t hex_at = kChecksumPrefix.size();
    const std::size_t payload_at = hex_at + 8 + kPayloadPrefix.size();
    if (all.size() < payload_at + kClosing.size() ||
        all.substr(hex_at + 8, kPayloadPrefix.size()) != kPayloadPrefix ||
        all.substr(all.size() - kClosing.size()) != kClosing)
        throw std::runtime_error("damaged: truncated or malformed checksum wrapper");
    const std::string hex_text(all.substr(hex_at, 8));
    if (hex_text.find_first_not_of("0123456789abcdef") != std::string::npos)
        throw std::runtime_error("damaged: malformed checksum");
    const auto stored = static_cast<std::uint32_t>(std::stoul(hex_text, nullptr, 16));
    const std::string_view payload =
        all.substr(payload_at, all.size() - payload_at - kClosing.size());
    const std::uint32_t actual = crc32(payload);
    if (actual != stored) {
        char message[128];
        std::snprintf(message, sizeof message,
                      "damaged: CRC-32 of the contents is %08" PRIx32 ", the file says %08" PRIx32,
                      actual, stored);
        throw std::runtime_error(message);
    }
    try {
        return json::parse(payload);
    } catch (const json::parse_error& e) {
        throw std::runtime_error("not valid JSON (" + without_json_tags(e.what()) + ")");
    }
}

void save_checkpoint(const std::string& dir, const RunState& state, bool current_is_damaged) {
    const fs::path current = fs::path(dir) / kCheckpointFile;
    const fs::path previous =
        fs::path(dir) / (current_is_damaged ? kDamagedCheckpointFile : kPreviousCheckpointFile);
    engine::AtomicFile file(current.string());
    file.write(checkpoint_text(run_state_to_json(state)));
    // Once the new one is complete on disk: the old one becomes the previous, the new one takes
    // its place. A crash in between leaves checkpoint.prev.json, which loading falls back to.
    file.commit([&] {
        std::error_code ec;
        if (!fs::exists(current, ec)) return;
        fs::rename(current, previous, ec);
        if (ec)
            throw std::runtime_error(previous.string() + ": cannot keep the replaced checkpoint (" +
                                     ec.message() + ")");
    });
}

std::optional<CheckpointRules> read_checkpoint_rules(const std::string& dir) {
    for (const char* name : {kCheckpointFile, kPreviousCheckpointFile}) {
        const std::string path = (fs::path(dir) / name).string();
        std::error_code ec;
        if (!fs::is_regular_file(path, ec)) continue;
        try {
            std::vector<std::string> notes;
            const json j =
                parse_checkpoint_text(engine::read_text(path, engine::kLargeFileCap), notes);
            const Fields f(j, "");
            CheckpointRules out;
            out.path = path;
            out.experiment = parse_experiment(f.at("experiment"), path + ":experiment");
            out.rule_changes =
                rule_changes_from_json(f.at("rule_changes"), out.experiment, "rule_changes");
            return out;
        } catch (const std::exception&) {
            continue;  // damaged: the previous one, else none (resuming says why)
        }
    }
    return std::nullopt;
}

LoadedCheckpoint load_checkpoint(const std::string& dir) {
    LoadedCheckpoint out;
    std::vector<std::string> problems;
    for (const char* name : {kCheckpointFile, kPreviousCheckpointFile}) {
        const std::string path = (fs::path(dir) / name).string();
        try {
            std::vector<std::string> notes;
            const json j =
                parse_checkpoint_text(engine::read_text(path, engine::kLargeFileCap), notes);
            out.state = run_state_from_json(j, path);
            out.path = path;
            for (const auto& p : problems)
                out.warnings.push_back(p + "; using " + path);
            for (const auto& n : notes)
                out.warnings.push_back(path + ": " + n);
            return out;
        } catch (const std::exception& e) {
            std::string message = without_json_tags(e.what());  // a resume warning's words
            if (message.rfind(path, 0) != 0) message = path + ": " + message;
            problems.push_back(message);
        }
    }
    throw std::runtime_error("no usable checkpoint in " + dir + ": " + problems[0] + "; " +
                             problems[1] +
                             ". Nothing can be resumed; a plain start (without --resume) into a "
                             "new --out folder runs the experiment from generation 0");
}

}  // namespace bhm::evo
