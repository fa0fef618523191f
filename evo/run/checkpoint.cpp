#include "evo/run/checkpoint.hpp"

#include <cinttypes>
#include <cstdio>
#include <filesystem>
#include <stdexcept>
#include <string_view>

#include "engine/io/atomic_file.hpp"
#include "engine/io/text_file.hpp"
#include "evo/experiment/json_fields.hpp"
#include "evo/experiment/json_reader.hpp"
#include "evo/run/crc32.hpp"

namespace bhm::evo {

using nlohmann::json;
namespace fs = std::filesystem;

namespace {

constexpr std::string_view kChecksumPrefix = "{\"checksum\":\"crc32:";
constexpr std::string_view kPayloadPrefix = "\",\"payload\":";
constexpr std::string_view kClosing = "}\n";

//! Reads the rows of run_state_fields() that `wanted` accepts, in the table's order, as
//! "LABEL: field: message" on the first one missing or wrong.
template <class Wanted>
RunState read_run_state(const json& j, const std::string& label, Wanted wanted) {
    try {
        CheckpointContext context;
        context.label = label;
        const Fields payload(j, "");
        RunState s;
        for (const auto& field : run_state_fields())
            if (field.read && wanted(std::string_view(field.key)))
                field.read(payload, field, s, context);
        return s;
    } catch (const FieldError& e) {
        throw std::runtime_error(label + ": " + e.what());
    } catch (const json::exception& e) {
        throw std::runtime_error(label + ": " + without_json_tags(e.what()));
    }
}

}  // namespace

json run_state_to_json(const RunState& s) {
    CheckpointContext context;
    context.fibre_outputs = s.experiment.evolution.cppn.fibre_outputs ? 3 : 0;
    return write_fields(run_state_fields(), s, context);
}

RunState run_state_from_json(const json& j, const std::string& label) {
    return read_run_state(j, label, [](std::string_view) { return true; });
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
            // Its format and the rules alone: the population is not developed.
            RunState rules = read_run_state(j, path, [](std::string_view key) {
                return key == "format" || key == "format_version" || key == "experiment" ||
                       key == "rule_changes";
            });
            return CheckpointRules{std::move(rules.experiment), std::move(rules.rule_changes),
                                   path};
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
