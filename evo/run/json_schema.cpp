#include "evo/run/json_schema.hpp"

#include <cinttypes>
#include <cstdio>

namespace bhm::evo {

std::string schema_markdown(std::span<const SchemaLine> lines, bool with_since) {
    std::string out = with_since
                          ? "| field | type | since | when | meaning |\n|---|---|---|---|---|\n"
                          : "| field | type | when | meaning |\n|---|---|---|---|\n";
    for (const auto& line : lines)
        out += "| `" + line.path + "` | " + line.type + " | " +
               (with_since ? std::to_string(line.since) + " | " : std::string()) +
               (line.when.empty() ? std::string("always") : line.when) + " | " + line.description +
               " |\n";
    return out;
}

const SchemaLine* find_schema_line(std::span<const SchemaLine> lines, std::string_view path) {
    for (const auto& line : lines)
        if (line.path == path) return &line;
    return nullptr;
}

std::string hex64_text(std::uint64_t value) {
    char buffer[24];
    std::snprintf(buffer, sizeof buffer, "%016" PRIx64, value);
    return buffer;
}

}  // namespace bhm::evo
