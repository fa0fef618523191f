#pragma once
// The checkpoint's schema as one field table (issue 41, json_schema.hpp): each field of
// checkpoint.json's payload with its JSON type, the format version that first may hold it, when
// it is written, what it means, and how it is written and read. The checkpoint's writer and
// reader (checkpoint.cpp) walk this table and those of the parts it holds (checkpoint_parts.hpp,
// cache_entry_json.hpp, rule_change_json.hpp), and docs/evolution.md's table is generated from
// them (checkpoint_schema_markdown; tests/evo/test_run_schema.cpp checks the two agree), so the
// table, the docs and the file cannot drift apart. The model is the experiment's field table
// (evo/experiment/experiment_fields.hpp); parts with a schema of their own (the experiment file,
// a genome, a FitnessReport, the continuum checks) are one row each, naming where theirs is.
#include <cstddef>
#include <optional>
#include <span>
#include <string>
#include <string_view>

#include "evo/genome/phenotype.hpp"
#include "evo/run/json_schema.hpp"
#include "evo/run/run_state.hpp"

namespace bhm::evo {

//! The format this build writes, and the oldest it reads.
inline constexpr int kCheckpointFormatVersion = 4;
inline constexpr int kOldestCheckpointFormatVersion = 1;
//! From this format on, cache entries are objects {hash, report}; before, positional arrays.
inline constexpr int kNamedCacheEntriesSince = 4;

//! What writing and reading a checkpoint know beyond the object at hand; reading fills it in as
//! the payload's rows are read in order.
struct CheckpointContext {
    std::string label;                       //!< the file, for the experiment reader's messages
    int version = kCheckpointFormatVersion;  //!< the payload's format_version
    std::optional<Developer> developer;      //!< the experiment's, to develop each genome
    double weight_range = 1.0;               //!< the CPPN's, to read genomes
    int fibre_outputs = 0;                   //!< the CPPN's fibre outputs, to name them (writing)
    std::size_t population = 0;              //!< members read (NEAT's species index them)
};

template <class Host>
using CheckpointFieldOf = JsonField<Host, CheckpointContext>;

//! The payload's fields (a RunState), in the order they are read.
std::span<const CheckpointFieldOf<RunState>> run_state_fields();

//! A line of the docs' table.
using CheckpointField = SchemaLine;
//! Every field, parts' fields included, parents before their children.
std::span<const CheckpointField> checkpoint_fields();
//! The field with this path ("history[].species"), or nullptr.
const CheckpointField* find_checkpoint_field(std::string_view path);

//! The table as docs/evolution.md holds it (a Markdown table, one row per field).
std::string checkpoint_schema_markdown();

}  // namespace bhm::evo
