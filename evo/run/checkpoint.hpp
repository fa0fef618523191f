#pragma once
// Checkpoints: the whole RunState as JSON, written after every generation. The write goes to a
// temporary file first (engine/io/atomic_file.hpp: every write, fsync and close checked); the
// previous checkpoint is renamed checkpoint.prev.json, then the new one takes its place, so a
// crash or a full disk at any moment leaves at least one complete checkpoint. Loading falls back
// to checkpoint.prev.json when checkpoint.json is missing or damaged, with a warning naming it.
//
// Format 2 (docs/evolution.md) wraps the payload with its CRC-32 so that damage which still
// parses as JSON (a flipped digit) is caught:
//   {"checksum":"crc32:XXXXXXXX","payload":{...,"format_version":2,...}}\n
// with the CRC over the exact bytes of the payload. Format 1 (the bare payload) is still read,
// with a warning that it is not verified. Format 3 added NEAT's state (its other additions are
// optional fields); format 4 writes each fitness cache entry as {"hash", "report"}, the report in
// its one form (fitness_json.hpp), where formats 1 to 3 wrote positional arrays, still read: the
// file's format_version says which form its cache holds (cache_entry_json.hpp). Every field,
// with the version that added it and how it is written and read: checkpoint_schema.hpp, whose
// table both the writer and the reader walk.
//
// Phenotypes are not stored: they are developed again from the genomes on load, and each one must
// match its recorded hash (a check that the decoder and the experiment are unchanged).
#include <optional>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "evo/evaluate/fitness_json.hpp"
#include "evo/run/checkpoint_schema.hpp"
#include "evo/run/run_state.hpp"

namespace bhm::evo {

inline constexpr const char* kCheckpointFile = "checkpoint.json";
inline constexpr const char* kPreviousCheckpointFile = "checkpoint.prev.json";
//! Where a damaged checkpoint.json goes when a resume fell back to checkpoint.prev.json: rotating
//! it into the backup slot would replace the one good checkpoint with the damaged one.
inline constexpr const char* kDamagedCheckpointFile = "checkpoint.damaged.json";

//! The payload, written by walking the checkpoint's field table (checkpoint_schema.hpp).
nlohmann::json run_state_to_json(const RunState& state);

//! The payload read by walking the same table. Throws std::runtime_error "LABEL: field.path:
//! message" on anything missing or inconsistent.
RunState run_state_from_json(const nlohmann::json& json, const std::string& label);

//! The file's text for a payload (format 2, above).
std::string checkpoint_text(const nlohmann::json& payload);
//! Verifies and parses a checkpoint file's text; notes get what the caller should warn about
//! (format 1). Throws std::runtime_error saying what is damaged.
nlohmann::json parse_checkpoint_text(const std::string& text, std::vector<std::string>& notes);

//! Writes DIR/checkpoint.json, keeping the previous one as DIR/checkpoint.prev.json. When
//! `current_is_damaged` (the run was resumed from checkpoint.prev.json), the old checkpoint.json
//! is moved to DIR/checkpoint.damaged.json instead and checkpoint.prev.json stays as it is.
void save_checkpoint(const std::string& dir, const RunState& state,
                     bool current_is_damaged = false);

//! What a checkpoint says of the rules, read without developing its population: the
//! experiment in force (the current rules) and every rule change. The checksummed record that
//! run.json's copy is checked against (run_directory.hpp, read_run_info).
struct CheckpointRules {
    Experiment experiment;
    std::vector<RuleChange> rule_changes;
    std::string path;  //!< the file read
};
//! From checkpoint.json, else checkpoint.prev.json; nullopt when neither exists or both are
//! damaged (loading them says why).
std::optional<CheckpointRules> read_checkpoint_rules(const std::string& dir);

struct LoadedCheckpoint {
    RunState state;
    std::string path;                   //!< the file actually used
    std::vector<std::string> warnings;  //!< e.g. why checkpoint.json was skipped
};
//! Loads DIR/checkpoint.json, or DIR/checkpoint.prev.json when the first is missing or corrupt.
//! Throws std::runtime_error naming both files and their problems when neither can be used.
LoadedCheckpoint load_checkpoint(const std::string& dir);

}  // namespace bhm::evo
