#include "app/cli/file_kind.hpp"

#include <fstream>

#include <nlohmann/json.hpp>

namespace bhm::app {

FileKind detect_file_kind(const std::string& path) {
    std::ifstream in(path, std::ios::binary);
    if (!in) return FileKind::Experiment;
    auto json = nlohmann::json::parse(in, nullptr, /*allow_exceptions=*/false);
    if (json.is_object() && json.contains("layers")) return FileKind::Body;
    return FileKind::Experiment;
}

}  // namespace bhm::app
