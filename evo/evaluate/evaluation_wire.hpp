#pragma once
// Byte messages for evaluating bodies in another process: what the MPI front end (app/mpi/)
// carries between rank 0 and the evaluating ranks. Pure C++ (no MPI here), so the round trips are
// tested without a launcher.
//
// Every message starts with the 4 bytes "BHMW", a u16 wire version and a u8 kind; integers are
// little-endian. A message of another version or kind is refused with a clear error rather than
// misread (ranks built from different commits must not mix).
//  - Rules: rules_id, then the experiment as experiment-format JSON (the lead's writer and
//    reader, so every field travels; encode_rules checks the round trip is exact).
//  - Job: batch_id, rules_id, index, then the body: 3 x i32 size, then one byte per cell.
//  - Result: batch_id, index, then the report as checkpoint JSON (report_to_json: the same fields
//    a checkpoint keeps; doubles round-trip exactly through nlohmann's shortest representation).
// Versions: 1 = results without a behaviour descriptor; 2 = results carry `behaviour`
// (evo/evaluate/behaviour.hpp), which novelty search needs from every rank. A version-1 rank would send
// results that silently lack it, so mixed versions are refused rather than read.
#include <cstdint>
#include <stdexcept>
#include <string>

#include "evo/evaluate/fitness.hpp"
#include "evo/experiment/experiment.hpp"

namespace bhm::evo {

// Version 3 jobs carry a body's per-voxel fibre axes (Body::fibre, issue 43) after its cells.
inline constexpr std::uint16_t kEvaluationWireVersion = 3;

struct WireError : std::runtime_error {
    using std::runtime_error::runtime_error;
};

struct RulesMessage {
    std::uint64_t rules_id = 0;
    Experiment rules;
};
struct JobMessage {
    std::uint64_t batch_id = 0;
    std::uint64_t rules_id = 0;
    std::uint32_t index = 0;  //!< position in the batch
    Body body;
};
struct ResultMessage {
    std::uint64_t batch_id = 0;
    std::uint32_t index = 0;
    FitnessReport report;
};

//! Throws WireError when the experiment would not come back identical from its JSON.
std::string encode_rules(const RulesMessage& message);
std::string encode_job(const JobMessage& message);
std::string encode_result(const ResultMessage& message);

//! Each throws WireError naming what is wrong (magic, version, kind, truncation, bad JSON).
RulesMessage decode_rules(const std::string& bytes);
JobMessage decode_job(const std::string& bytes);
ResultMessage decode_result(const std::string& bytes);

}  // namespace bhm::evo
