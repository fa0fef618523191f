#pragma once
// The schemas of run.json and champion.json as field tables (issue 41, json_schema.hpp): the
// writer (run_output.cpp) and the readers (run_directory.cpp) both walk them, and
// docs/evolution.md's tables are generated from them (run_file_schema_markdown;
// tests/evo/test_run_schema.cpp checks they agree). Neither file has format versions: a field
// added later is read where present (its `when` says which files lack it).
#include <span>
#include <string>
#include <string_view>

#include "evo/experiment/experiment.hpp"
#include "evo/run/json_schema.hpp"
#include "evo/run/run_directory.hpp"
#include "evo/run/run_state.hpp"

namespace bhm::evo {

//! What writing and reading run.json or champion.json know beyond the object. Read errors are
//! FieldErrors naming the field alone; the reader puts "PATH:" before them.
struct RunFileContext {
    std::string path;  //!< the file, for the experiment and body readers
    //! champion.json: the experiment its body is of; null when only its summary is read (the
    //! body and the genome, which need it, are then skipped).
    const Experiment* experiment = nullptr;
    std::string run_dir;  //!< champion.json: where run.json is, for messages
    int version = 1;      //!< no versions: fields added later have a `when`
    //! champion.json: the measure its fitness is of, as the file names it (read into here: the
    //! champion's rules are not part of the ChampionRecord).
    FitnessMeasure measure = FitnessMeasure::ComFinal3d;
};

template <class Host>
using RunFileFieldOf = JsonField<Host, RunFileContext>;

//! run.json: bhm_version, seed, the experiment as started, the rule changes.
std::span<const RunFileFieldOf<RunInfo>> run_info_fields();
//! champion.json: the champion under the experiment in the context (its name is written for people
//! and the Python module, not read back; its measure is read into the context).
std::span<const RunFileFieldOf<ChampionRecord>> champion_file_fields();

//! The table of "run.json" or "champion.json" as docs/evolution.md holds it (no since column).
std::string run_file_schema_markdown(std::string_view file);

}  // namespace bhm::evo
