#pragma once
// Every reader of what a run leaves in its directory (run.json, fitness.csv, champion.json), beside
// the writer (run_output.hpp) and the checkpoint (checkpoint.hpp): the CLI's exports, the studio's
// view of a run directory and the Python module all read through here. Each reader names the
// file, and the field or row, in what it throws.
#include <cstdint>
#include <optional>
#include <string>
#include <vector>

#include "evo/evaluate/exploit_flags.hpp"
#include "evo/experiment/experiment.hpp"
#include "evo/run/member_summary.hpp"
#include "evo/run/run_state.hpp"

namespace bhm::evo {

inline constexpr const char* kRunInfoFile = "run.json";
inline constexpr const char* kFitnessCsvFile = "fitness.csv";
inline constexpr const char* kChampionFile = "champion.json";

//! run.json: the experiment as the run was started and every change of rules since (fitness,
//! and physics where a change set it). Its fields: run_file_schema.hpp.
struct RunInfo {
    std::string bhm_version;  //!< the bhm that started the run
    std::uint64_t seed = 0;
    Experiment started;
    std::vector<RuleChange> rule_changes;  //!< in order
    //! The rules in force as the run's checkpoint records them (checksummed), where it has one.
    std::optional<Experiment> checkpoint_rules;
    //! Where run.json disagreed with the checkpoint (and the checkpoint's record was taken).
    std::vector<std::string> warnings;
    //! The rules in force now: the checkpoint's where there is one, else the started experiment
    //! with the last change's fitness section, the physics of the last change that set physics
    //! and the continuum checks of the last change that set them.
    Experiment current() const;
};
//! run.json, checked against the checkpoint: run.json is rewritten by the run but not
//! checksummed, so where its rule changes or the rules they make differ from the checkpoint's,
//! the checkpoint's are taken and a warning names both files (a physics change present only in
//! run.json made exports and `bhm verify` use it). Throws std::runtime_error "PATH: field:
//! message" when run.json is missing or malformed.
RunInfo read_run_info(const std::string& run_dir);

//! champion.json: the best individual found so far, under the rules in force when it was found.
//! The member's summary (id, fitness, age, voxels, active voxels, exploit flags; what the file does
//! not hold keeps MemberSummary's default) and what only a champion has.
struct ChampionFile : MemberSummary {
    int generation_found = 0;
    Body body;  //!< framed, workspace-sized phenotype
};
//! Reads champion.json and checks its body against the experiment (a champion of another
//! experiment would name materials it does not define). Throws std::runtime_error naming the file.
ChampionFile read_champion_file(const std::string& run_dir, const Experiment& experiment);

//! A champion file's summary without its body and genome (which need the experiment): the
//! member's summary, the generation that found it and the measure its fitness is of. The studio's
//! list of a run's champions reads each file through here. Throws std::runtime_error "PATH:field:
//! message" on a field missing or wrong.
struct ChampionSummary : MemberSummary {
    int generation_found = 0;
    FitnessMeasure measure = FitnessMeasure::ComFinal3d;
};
ChampionSummary read_champion_summary(const std::string& path);

inline constexpr const char* kChampionsDir = "champions";
//! Every champion a run has had (champions/gen-NNNNN.json, oldest first), each read and checked
//! as read_champion_file; champion.json alone where the folder is empty or missing.
std::vector<ChampionFile> read_champion_history(const std::string& run_dir,
                                                const Experiment& experiment);

//! fitness.csv with its columns found by name (columns added later do not break a reader). A
//! row that cannot be read (a partial last line after a crash, or one being appended) ends the
//! table: the rows before it are kept and `problem` names it.
struct FitnessTable {
    std::vector<std::string> header;
    std::vector<std::vector<double>> rows;
    std::string problem;  //!< "" when every row was read
    //! The column's index; throws std::runtime_error naming the file when it is absent.
    std::size_t column(const std::string& name) const;
    std::string path;
};
//! Throws std::runtime_error when the file cannot be read or has no header.
FitnessTable read_fitness_table(const std::string& run_dir);
//! population.csv (population_csv.hpp), read as fitness.csv is: its columns by name, a row that
//! cannot be read ends the table. Throws std::runtime_error when the file cannot be read or has
//! no header.
FitnessTable read_population_table(const std::string& run_dir);

}  // namespace bhm::evo
