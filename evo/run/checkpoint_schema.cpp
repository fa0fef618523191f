#include "evo/run/checkpoint_schema.hpp"

#include <array>

namespace bhm::evo {

namespace {

constexpr const char* kBeforeExploits = "absent in checkpoints written before exploit detection";
constexpr const char* kBeforeEarlyEnd =
    "absent in checkpoints written before evaluations could end early";

// Formats: 1 the bare payload; 2 wrapped with its CRC-32 (behaviour descriptors came in 2);
// 3 NEAT's state (novelty search, early ends, physics changes and the continuum checks came in
// 3, each optional); 4 cache entries as named objects.
constexpr std::array kFields = {
    CheckpointField{"format", "string", 1, "", "always `bhm-evolution-checkpoint`"},
    CheckpointField{"format_version", "integer", 1, "",
                    "this file's format: it says which form the cache holds"},
    CheckpointField{"bhm_version", "string", 1, "", "the bhm that wrote it"},
    CheckpointField{"seed", "hex", 1, "", "the run's seed"},
    CheckpointField{"generation", "integer", 1, "", "the last completed generation (-1: none)"},
    CheckpointField{"next_id", "integer", 1, "", "the id the next new individual gets"},
    CheckpointField{"rng", "array", 1, "", "the xoshiro256** state: 4 hex words, not all zero"},
    CheckpointField{"rules_version", "integer", 1, "", "bumped by every rule change"},
    CheckpointField{"elapsed_s", "number", 1, "",
                    "wall time of the completed generations, across resumes (paused time "
                    "excluded)"},
    CheckpointField{"experiment", "experiment", 1, "",
                    "the rules in force, as the experiment file writes them: the fitness of the "
                    "last change, the physics of the last physics change"},
    CheckpointField{"population", "objects", 1, "",
                    "the members in selection order; each phenotype is developed again on load "
                    "and checked against its hash"},
    CheckpointField{"population[].id", "integer", 1, "", "the member's id"},
    CheckpointField{"population[].parent_id", "integer", 1, "", "its parent's id (-1: none)"},
    CheckpointField{"population[].age", "integer", 1, "", "AFPO age"},
    CheckpointField{"population[].born_generation", "integer", 1, "", "the generation it was made"},
    CheckpointField{"population[].evaluated", "boolean", 1, "", "it has a result"},
    CheckpointField{"population[].valid", "boolean", 1, "", "it meets the constraints"},
    CheckpointField{"population[].phenotype_hash", "hex", 1, "",
                    "the hash of the body its genome develops into"},
    CheckpointField{"population[].genome", "genome", 1, "",
                    "the CPPN (evo/genome/genome.hpp); NEAT's genes carry innovation numbers "
                    "from format 3"},
    CheckpointField{"population[].report", "report", 1, "",
                    "its FitnessReport (evo/evaluate/fitness_json.hpp)"},
    CheckpointField{"pareto_rank", "array", 1, "", "per member, from the last selection"},
    CheckpointField{"history", "objects", 1, "",
                    "one row per completed generation (fitness.csv's rows)"},
    CheckpointField{"history[].generation", "integer", 1, "", "the generation"},
    CheckpointField{"history[].evaluations", "integer", 1, "",
                    "new individuals that needed a result"},
    CheckpointField{"history[].simulations", "integer", 1, "", "of those, the ones simulated"},
    CheckpointField{"history[].best_fitness", "number", 1, "", "after selection"},
    CheckpointField{"history[].median_fitness", "number", 1, "", "after selection"},
    CheckpointField{"history[].best_age", "integer", 1, "", "the best member's age"},
    CheckpointField{"history[].best_id", "integer", 1, "", "the best member's id"},
    CheckpointField{"history[].diverged", "integer", 1, "", "simulations that diverged"},
    CheckpointField{"history[].wall_s", "number", 1, "", "wall time since the start at its end"},
    CheckpointField{"history[].rules_version", "integer", 1, "", "the rules it ran under"},
    CheckpointField{"history[].best_exploits", "exploits", 1, kBeforeExploits,
                    "the best member's exploit flags"},
    CheckpointField{"history[].flagged_members", "integer", 1, kBeforeExploits,
                    "members raising any exploit flag"},
    CheckpointField{"history[].species", "integer", 3, "", "NEAT's species (0 otherwise)"},
    CheckpointField{"history[].ended_early", "integer", 3, kBeforeEarlyEnd,
                    "simulations that ended early because the motion repeated"},
    CheckpointField{"history[].mean_simulated_s", "number", 3, kBeforeEarlyEnd,
                    "their mean simulated time"},
    CheckpointField{"history[].best_simulated_s", "number", 3, kBeforeEarlyEnd,
                    "where the best member's simulation stopped"},
    CheckpointField{"history[].best_periodic_residual", "number", 3, kBeforeEarlyEnd,
                    "its last period-to-period residual (voxel lengths)"},
    CheckpointField{"history[].novelty", "object", 3, "novelty search runs",
                    "the generation's novelty figures"},
    CheckpointField{"history[].novelty.best_novelty", "number", 3, "novelty search runs",
                    "the highest novelty after selection"},
    CheckpointField{"history[].novelty.median_novelty", "number", 3, "novelty search runs",
                    "the median novelty"},
    CheckpointField{"history[].novelty.archive_size", "integer", 3, "novelty search runs",
                    "archive entries after this generation"},
    CheckpointField{"history[].novelty.archive_added", "integer", 3, "novelty search runs",
                    "entries this generation added"},
    CheckpointField{"history[].novelty.archive_threshold", "number", 3, "novelty search runs",
                    "the threshold after this generation"},
    CheckpointField{"history[].novelty.champion_fitness", "number", 3, "novelty search runs",
                    "the best fitness so far"},
    CheckpointField{"history[].verify", "loop check row", 3, "runs with continuum checks",
                    "the generation's checks (evo/run/loop_check_json.hpp)"},
    CheckpointField{"rule_changes", "objects", 1, "",
                    "every rule change in order, the form run.json's holds too "
                    "(evo/run/rule_change_json.hpp)"},
    CheckpointField{"rule_changes[].generation", "integer", 1, "", "the first generation under it"},
    CheckpointField{"rule_changes[].fitness", "fitness", 1, "",
                    "the fitness section in force from then, as the experiment file writes it"},
    CheckpointField{"rule_changes[].physics", "physics", 3, "a change that set the physics",
                    "materials, actuation and damping (evo/run/physics_rules.hpp)"},
    CheckpointField{"rule_changes[].verify", "verify settings", 3,
                    "a change that set the continuum checks", "their policy"},
    CheckpointField{"cache_capacity", "integer", 1, "", "the fitness cache's size limit"},
    CheckpointField{"cache", "objects", 1, "",
                    "the fitness cache, oldest first; formats 1 to 3 hold positional arrays"},
    CheckpointField{"cache[].hash", "hex", 4, "", "the phenotype's hash"},
    CheckpointField{"cache[].report", "report", 4, "",
                    "its FitnessReport (evo/evaluate/fitness_json.hpp), as simulated"},
    CheckpointField{"neat", "object", 3, "NEAT runs", "innovation counters and species"},
    CheckpointField{"neat.next_innovation", "integer", 3, "NEAT runs",
                    "the next innovation number"},
    CheckpointField{"neat.next_node_id", "integer", 3, "NEAT runs", "the next hidden node id"},
    CheckpointField{"neat.next_species_id", "integer", 3, "NEAT runs", "the next species id"},
    CheckpointField{"neat.threshold", "number", 3, "NEAT runs", "the compatibility threshold"},
    CheckpointField{"neat.species", "objects", 3, "NEAT runs", "every species"},
    CheckpointField{"neat.species[].id", "integer", 3, "NEAT runs", "its id"},
    CheckpointField{"neat.species[].representative", "genome", 3, "NEAT runs",
                    "the genome members are compared with"},
    CheckpointField{"neat.species[].best_fitness", "number", 3, "NEAT runs", "its best fitness"},
    CheckpointField{"neat.species[].last_improved", "integer", 3, "NEAT runs",
                    "the generation its best last rose"},
    CheckpointField{"neat.species[].created", "integer", 3, "NEAT runs", "the generation it began"},
    CheckpointField{"neat.species[].members", "array", 3, "NEAT runs",
                    "indices into the population"},
    CheckpointField{"novelty_archive", "object", 3, "novelty search runs", "the archive"},
    CheckpointField{"novelty_archive.threshold", "number", 3, "novelty search runs",
                    "the novelty an entry needs"},
    CheckpointField{"novelty_archive.entries", "array", 3, "novelty search runs",
                    "behaviour descriptors"},
    CheckpointField{"pending_checks", "pending checks", 3, "runs with continuum checks",
                    "bodies picked for checking whose results land later"},
    CheckpointField{"loop_checks", "array", 3, "runs with continuum checks",
                    "every check applied so far (evo/run/loop_check_json.hpp)"},
    CheckpointField{"champion", "object or null", 1, "", "the best individual so far"},
    CheckpointField{"champion.generation_found", "integer", 1, "champion not null",
                    "the generation that found it"},
    CheckpointField{"champion.individual", "individual", 1, "champion not null",
                    "as a member of `population`"},
};

}  // namespace

std::span<const CheckpointField> checkpoint_fields() {
    return kFields;
}

const CheckpointField* find_checkpoint_field(std::string_view path) {
    for (const auto& f : kFields)
        if (path == f.path) return &f;
    return nullptr;
}

std::string checkpoint_schema_markdown() {
    std::string out = "| field | type | since | when | meaning |\n|---|---|---|---|---|\n";
    for (const auto& f : kFields)
        out += std::string("| `") + f.path + "` | " + f.type + " | " + std::to_string(f.since) +
               " | " + (*f.when ? f.when : "always") + " | " + f.description + " |\n";
    return out;
}

}  // namespace bhm::evo
