#include "app/cli/file_kind.hpp"

#include <nlohmann/json.hpp>

#include "engine/io/text_file.hpp"

namespace bhm::app {

FileKind detect_file_kind(const std::string& path) {
    std::string text;
    try {
        // Through the capped reader: /dev/zero or a pipe must not be streamed into memory here.
        text = engine::read_text(path, engine::kTextFileCap);
    } catch (const engine::FileReadError&) {
        return FileKind::Experiment;  // its loader reports the problem with the file's name
    }
    auto json = nlohmann::json::parse(text, nullptr, /*allow_exceptions=*/false);
    if (json.is_object() && json.contains("layers")) return FileKind::Body;
    return FileKind::Experiment;
}

}  // namespace bhm::app
