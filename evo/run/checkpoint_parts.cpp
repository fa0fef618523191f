#include "evo/run/checkpoint_parts.hpp"

#include <array>
#include <stdexcept>

#include "evo/evaluate/exploit_flags.hpp"
#include "evo/evaluate/fitness_json.hpp"
#include "evo/genome/genome.hpp"
#include "evo/run/loop_check_json.hpp"
#include "evo/run/report_field.hpp"

namespace bhm::evo {

using nlohmann::json;

namespace {

using Context = CheckpointContext;

constexpr const char* kBeforeExploits = "absent in checkpoints written before exploit detection";
constexpr const char* kBeforeEarlyEnd =
    "absent in checkpoints written before evaluations could end early";

// --- a member of the population ----------------------------------------------------------------

void write_genome(const Individual& ind, const char* key, json& out, const Context& context) {
    out[key] = genome_to_json(ind.genome, context.fibre_outputs);
}
//! The genome, and the body it develops into (phenotypes are not stored).
void read_genome(const Fields& f, const CheckpointFieldOf<Individual>& field, Individual& ind,
                 Context& context) {
    try {
        ind.genome = genome_from_json(f.at(field.key), context.weight_range);
    } catch (const std::invalid_argument& e) {
        throw FieldError(f.join("") + "." + e.what());
    }
    ind.phenotype = context.developer->develop(ind.genome, ind.controller);
}

//! evolution.controller coevolve: the controller CPPN, read before the genome, which develops
//! with it. Written where the member has one (an empty controller is the same as none).
void write_controller(const Individual& ind, const char* key, json& out, const Context&) {
    if (!ind.controller.edges.empty() || !ind.controller.hidden.empty())
        out[key] = genome_to_json(ind.controller);
}
void read_controller(const Fields& f, const CheckpointFieldOf<Individual>& field, Individual& ind,
                     Context& context) {
    if (!f.has(field.key)) return;
    try {
        ind.controller = genome_from_json(f.at(field.key), context.weight_range);
    } catch (const std::invalid_argument& e) {
        throw FieldError(f.join("") + "." + e.what());
    }
}

void write_phenotype_hash(const Individual& ind, const char* key, json& out, const Context&) {
    out[key] = hex64_text(ind.phenotype.hash);
}
void read_phenotype_hash(const Fields& f, const CheckpointFieldOf<Individual>& field,
                         Individual& ind, Context&) {
    if (ind.phenotype.hash != f.hex64(field.key))
        f.fail(field.key,
               "the genome develops into a different body (decoder or experiment changed?)");
}

constexpr std::array kIndividual = {
    member_field<&Individual::id, Context>("id", 1, "", "the member's id"),
    member_field<&Individual::parent_id, Context>("parent_id", 1, "", "its parent's id (-1: none)"),
    member_field<&Individual::age, Context>("age", 1, "", "AFPO age"),
    member_field<&Individual::born_generation, Context>("born_generation", 1, "",
                                                        "the generation it was made"),
    member_field<&Individual::evaluated, Context>("evaluated", 1, "", "it has a result"),
    member_field<&Individual::valid, Context>("valid", 1, "", "it meets the constraints"),
    CheckpointFieldOf<Individual>{"controller", "genome", 4, "evolution.controller.mode coevolve",
                                  "the controller CPPN (evo/genome/controller.hpp)",
                                  write_controller, read_controller},
    CheckpointFieldOf<Individual>{"genome", "genome", 1, "",
                                  "the CPPN (evo/genome/genome.hpp); NEAT's genes carry "
                                  "innovation numbers from format 3",
                                  write_genome, read_genome},
    CheckpointFieldOf<Individual>{"phenotype_hash", "hex", 1, "",
                                  "the hash of the body its genome develops into, checked on load",
                                  write_phenotype_hash, read_phenotype_hash},
    report_field<&Individual::report, Context>("report", 1, "",
                                               "its FitnessReport (evo/evaluate/fitness_json.hpp)"),
};

// --- a history row -----------------------------------------------------------------------------

void write_best_exploits(const HistoryRow& h, const char* key, json& out, const Context&) {
    out[key] = exploits_to_json(h.best_exploits);
}
void read_best_exploits(const Fields& f, const CheckpointFieldOf<HistoryRow>& field, HistoryRow& h,
                        Context& context) {
    if (field.skipped(f, context)) return;
    try {
        h.best_exploits = exploits_from_json(f.at(field.key));
    } catch (const std::invalid_argument& e) {
        throw FieldError(f.join("") + "." + e.what());
    }
}

void write_novelty(const HistoryRow& h, const char* key, json& out, const Context& context) {
    if (h.novelty) out[key] = write_fields(novelty_row_fields(), *h.novelty, context);
}
void read_novelty(const Fields& f, const CheckpointFieldOf<HistoryRow>& field, HistoryRow& h,
                  Context& context) {
    if (field.skipped(f, context)) return;
    h.novelty = read_part(novelty_row_fields(), f.at(field.key), f.join(field.key), context);
}

void write_verify(const HistoryRow& h, const char* key, json& out, const Context&) {
    if (h.verify) out[key] = loop_check_row_to_json(*h.verify);
}
void read_verify(const Fields& f, const CheckpointFieldOf<HistoryRow>& field, HistoryRow& h,
                 Context& context) {
    if (field.skipped(f, context)) return;
    h.verify = loop_check_row_from_json(f.at(field.key), f.join(field.key));
}

template <auto M>
constexpr CheckpointFieldOf<HistoryRow> history(const char* key, int since, const char* when,
                                                const char* description) {
    return member_field<M, Context>(key, since, when, description);
}

constexpr std::array kHistoryRow = {
    history<&HistoryRow::generation>("generation", 1, "", "the generation"),
    history<&HistoryRow::evaluations>("evaluations", 1, "", "new individuals that needed a result"),
    history<&HistoryRow::simulations>("simulations", 1, "", "of those, the ones simulated"),
    history<&HistoryRow::best_fitness>("best_fitness", 1, "", "after selection"),
    history<&HistoryRow::median_fitness>("median_fitness", 1, "", "after selection"),
    history<&HistoryRow::best_age>("best_age", 1, "", "the best member's age"),
    history<&HistoryRow::best_id>("best_id", 1, "", "the best member's id"),
    history<&HistoryRow::diverged>("diverged", 1, "", "simulations that diverged"),
    history<&HistoryRow::wall_s>("wall_s", 1, "", "wall time since the start at its end"),
    history<&HistoryRow::rules_version>("rules_version", 1, "", "the rules it ran under"),
    CheckpointFieldOf<HistoryRow>{"best_exploits", "exploits", 1, kBeforeExploits,
                                  "the best member's exploit flags", write_best_exploits,
                                  read_best_exploits},
    history<&HistoryRow::flagged_members>("flagged_members", 1, kBeforeExploits,
                                          "members raising any exploit flag"),
    history<&HistoryRow::species>("species", 3, "", "NEAT's species (0 otherwise)"),
    history<&HistoryRow::ended_early>("ended_early", 3, kBeforeEarlyEnd,
                                      "simulations that ended early because the motion repeated"),
    history<&HistoryRow::mean_simulated_s>("mean_simulated_s", 3, kBeforeEarlyEnd,
                                           "their mean simulated time"),
    history<&HistoryRow::best_simulated_s>("best_simulated_s", 3, kBeforeEarlyEnd,
                                           "where the best member's simulation stopped"),
    history<&HistoryRow::best_periodic_residual>(
        "best_periodic_residual", 3, kBeforeEarlyEnd,
        "its last period-to-period residual (voxel lengths)"),
    CheckpointFieldOf<HistoryRow>{"novelty", "object", 3, "novelty search runs",
                                  "the generation's novelty figures", write_novelty, read_novelty,
                                  describe_object<novelty_row_fields>},
    CheckpointFieldOf<HistoryRow>{"verify", "loop check row", 3, "runs with continuum checks",
                                  "the generation's checks (evo/run/loop_check_json.hpp)",
                                  write_verify, read_verify},
};

constexpr std::array kNoveltyRow = {
    member_field<&NoveltyRow::best_novelty, Context>("best_novelty", 1, "",
                                                     "the highest novelty after selection"),
    member_field<&NoveltyRow::median_novelty, Context>("median_novelty", 1, "",
                                                       "the median novelty"),
    member_field<&NoveltyRow::archive_size, Context>("archive_size", 1, "",
                                                     "archive entries after this generation"),
    member_field<&NoveltyRow::archive_added, Context>("archive_added", 1, "",
                                                      "entries this generation added"),
    member_field<&NoveltyRow::archive_threshold, Context>("archive_threshold", 1, "",
                                                          "the threshold after this generation"),
    member_field<&NoveltyRow::champion_fitness, Context>("champion_fitness", 1, "",
                                                         "the best fitness so far"),
};

// --- NEAT --------------------------------------------------------------------------------------

void write_species(const NeatState& n, const char* key, json& out, const Context& context) {
    out[key] = write_objects<neat_species_fields>(n.species, context);
}
//! Every species, and every member of the population in exactly one of them.
void read_species(const Fields& f, const CheckpointFieldOf<NeatState>& field, NeatState& n,
                  Context& context) {
    n.species = read_objects<neat_species_fields, NeatSpecies>(f.array(field.key),
                                                               f.join(field.key), context);
    std::size_t members = 0;
    for (const auto& s : n.species)
        members += s.members.size();
    if (members != context.population)
        f.fail(field.key, "every population member in one species expected");
}

constexpr std::array kNeatState = {
    member_field<&NeatState::next_innovation, Context>("next_innovation", 1, "",
                                                       "the next innovation number"),
    member_field<&NeatState::next_node_id, Context>("next_node_id", 1, "",
                                                    "the next hidden node id"),
    member_field<&NeatState::next_species_id, Context>("next_species_id", 1, "",
                                                       "the next species id"),
    member_field<&NeatState::threshold, Context>("threshold", 1, "", "the compatibility threshold"),
    CheckpointFieldOf<NeatState>{"species", "objects", 1, "", "every species", write_species,
                                 read_species, describe_object<neat_species_fields>},
};

void write_representative(const NeatSpecies& s, const char* key, json& out,
                          const Context& context) {
    out[key] = genome_to_json(s.representative, context.fibre_outputs);
}
void read_representative(const Fields& f, const CheckpointFieldOf<NeatSpecies>& field,
                         NeatSpecies& s, Context& context) {
    try {
        s.representative = genome_from_json(f.at(field.key), context.weight_range);
    } catch (const std::invalid_argument& e) {
        throw FieldError(f.join(field.key) + ": " + e.what());
    }
}

void write_members(const NeatSpecies& s, const char* key, json& out, const Context&) {
    out[key] = s.members;
}
void read_members(const Fields& f, const CheckpointFieldOf<NeatSpecies>& field, NeatSpecies& s,
                  Context& context) {
    for (const auto& m : f.array(field.key)) {
        if (!m.is_number_integer() || m.get<std::int64_t>() < 0 ||
            m.get<std::size_t>() >= context.population)
            f.fail(field.key, "expected indices into the population");
        s.members.push_back(m.get<int>());
    }
    if (s.members.empty()) f.fail(field.key, "a species has at least one member");
}

constexpr std::array kNeatSpecies = {
    member_field<&NeatSpecies::id, Context>("id", 1, "", "its id"),
    CheckpointFieldOf<NeatSpecies>{"representative", "genome", 1, "",
                                   "the genome members are compared with", write_representative,
                                   read_representative},
    // -inf cannot be stored in JSON (it is written as null): a species always has a best.
    member_field<&NeatSpecies::best_fitness, Context>("best_fitness", 1, "", "its best fitness"),
    member_field<&NeatSpecies::last_improved, Context>("last_improved", 1, "",
                                                       "the generation its best last rose"),
    member_field<&NeatSpecies::created, Context>("created", 1, "", "the generation it began"),
    CheckpointFieldOf<NeatSpecies>{"members", "array", 1, "", "indices into the population",
                                   write_members, read_members},
};

// --- novelty search's archive ------------------------------------------------------------------

void write_threshold(const NoveltyArchive& a, const char* key, json& out, const Context&) {
    out[key] = a.threshold;
}
void read_threshold(const Fields& f, const CheckpointFieldOf<NoveltyArchive>& field,
                    NoveltyArchive& a, Context&) {
    a.threshold = f.number(field.key);
    if (!(a.threshold > 0.0)) f.fail(field.key, "must be > 0");
}

void write_entries(const NoveltyArchive& a, const char* key, json& out, const Context&) {
    out[key] = a.entries;
}
void read_entries(const Fields& f, const CheckpointFieldOf<NoveltyArchive>& field,
                  NoveltyArchive& a, Context&) {
    const auto& entries = f.array(field.key);
    for (std::size_t i = 0; i < entries.size(); ++i) {
        auto entry = behaviour_from_json(entries[i], item(f.join(field.key), i));
        if (entry.empty()) f.fail(field.key, "an archive entry is a whole descriptor");
        a.entries.push_back(std::move(entry));
    }
}

constexpr std::array kNoveltyArchive = {
    CheckpointFieldOf<NoveltyArchive>{"threshold", "number", 1, "", "the novelty an entry needs",
                                      write_threshold, read_threshold},
    CheckpointFieldOf<NoveltyArchive>{"entries", "array", 1, "", "behaviour descriptors",
                                      write_entries, read_entries},
};

// --- the champion ------------------------------------------------------------------------------

void write_champion_individual(const ChampionRecord& c, const char* key, json& out,
                               const Context& context) {
    out[key] = write_fields(individual_fields(), c.individual, context);
}
void read_champion_individual(const Fields& f, const CheckpointFieldOf<ChampionRecord>& field,
                              ChampionRecord& c, Context& context) {
    c.individual = read_part(individual_fields(), f.at(field.key), f.join(field.key), context);
}

constexpr std::array kChampion = {
    member_field<&ChampionRecord::generation_found, Context>("generation_found", 1, "",
                                                             "the generation that found it"),
    CheckpointFieldOf<ChampionRecord>{"individual", "individual", 1, "",
                                      "as a member of `population`", write_champion_individual,
                                      read_champion_individual},
};

}  // namespace

std::span<const CheckpointFieldOf<Individual>> individual_fields() {
    return kIndividual;
}
std::span<const CheckpointFieldOf<HistoryRow>> history_row_fields() {
    return kHistoryRow;
}
std::span<const CheckpointFieldOf<NoveltyRow>> novelty_row_fields() {
    return kNoveltyRow;
}
std::span<const CheckpointFieldOf<NeatState>> neat_state_fields() {
    return kNeatState;
}
std::span<const CheckpointFieldOf<NeatSpecies>> neat_species_fields() {
    return kNeatSpecies;
}
std::span<const CheckpointFieldOf<NoveltyArchive>> novelty_archive_fields() {
    return kNoveltyArchive;
}
std::span<const CheckpointFieldOf<ChampionRecord>> champion_fields() {
    return kChampion;
}

}  // namespace bhm::evo
