#pragma once
// The checkpoint's schema as one field table (issue 41): each field of checkpoint.json's payload
// with its JSON type, the format version that first may hold it, when it is written, and what it
// means. docs/evolution.md's table of the checkpoint is generated from it
// (checkpoint_schema_markdown; tests/evo/test_run_schema.cpp checks the two agree), and the same
// test checks what the writer (checkpoint.cpp) writes against it, so the table, the docs and the
// file cannot drift apart. The model is the experiment's field table
// (evo/experiment/experiment_fields.hpp); parts with a schema of their own (the experiment file,
// a genome, a FitnessReport, the continuum checks) are one row each, naming where theirs is.
#include <span>
#include <string>
#include <string_view>

namespace bhm::evo {

//! The format this build writes, and the oldest it reads.
inline constexpr int kCheckpointFormatVersion = 4;
inline constexpr int kOldestCheckpointFormatVersion = 1;
//! From this format on, cache entries are objects {hash, report}; before, positional arrays.
inline constexpr int kNamedCacheEntriesSince = 4;

struct CheckpointField {
    //! JSON path in the payload; "[]" stands for every element of an array: "cache[].report".
    const char* path;
    //! "string", "hex" (a string of up to 16 lowercase hex digits), "integer", "number",
    //! "boolean", "object", "array" (of values), "objects" (an array of objects, each described
    //! by the rows under "path[]."), "object or null", or a part with its own schema, named by
    //! where it is described ("experiment", "genome", "report", ...).
    const char* type;
    int since;         //!< the first format version that may hold it
    const char* when;  //!< "" when every checkpoint of that version holds it, else when it does
    const char* description;
};

//! Every field, parents before their children, in the order the writer writes them.
std::span<const CheckpointField> checkpoint_fields();
//! The field with this path ("history[].species"), or nullptr.
const CheckpointField* find_checkpoint_field(std::string_view path);

//! The table as docs/evolution.md holds it (a Markdown table, one row per field).
std::string checkpoint_schema_markdown();

}  // namespace bhm::evo
