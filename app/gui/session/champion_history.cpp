#include "app/gui/session/champion_history.hpp"

#include <algorithm>
#include <fstream>
#include <sstream>

#include <nlohmann/json.hpp>

#include "engine/io/text_file.hpp"
#include "evo/experiment/experiment_io.hpp"
#include "evo/experiment/json_reader.hpp"
#include "evo/run/run_directory.hpp"

namespace bhm::app::gui {

namespace fs = std::filesystem;
using nlohmann::json;

namespace {

json read_json(const std::string& path) {
    const std::string text = engine::read_text(path, engine::kTextFileCap);
    try {
        return json::parse(text);
    } catch (const json::exception& e) {
        throw std::runtime_error(path + ": not valid JSON (" + evo::without_json_tags(e.what()) +
                                 ")");
    }
}

}  // namespace

bool ChampionHistory::refresh(const std::string& run_dir) {
    if (run_dir != dir_) {
        dir_ = run_dir;
        entries_.clear();
        seen_.clear();
        checked_ = {};
    }
    const auto now = std::chrono::steady_clock::now();
    if (dir_.empty() || now - checked_ < std::chrono::milliseconds(500)) return false;
    checked_ = now;
    std::error_code ec;
    bool changed = false;
    for (fs::directory_iterator it(fs::path(dir_) / "champions", ec), end; !ec && it != end;
         it.increment(ec)) {
        const auto& p = it->path();
        if (p.extension() != ".json" || !p.filename().string().starts_with("gen-")) continue;
        std::error_code time_ec;
        const auto mtime = fs::last_write_time(p, time_ec);
        const auto key = p.string();
        if (auto s = seen_.find(key); s != seen_.end() && s->second == mtime) continue;
        try {
            // Through the run directory's reader of champion files (evo/run/run_directory.hpp),
            // which walks the file's field table: its errors name the file and the field.
            const evo::ChampionSummary c = evo::read_champion_summary(key);
            ChampionEntry e;
            e.generation = c.generation_found;
            e.id = c.id;
            e.fitness = c.fitness;
            e.measure = c.measure;
            e.voxels = c.voxels;
            e.active_voxels = c.active_voxels;
            e.exploits = c.exploits;
            e.path = key;
            std::erase_if(entries_, [&](const ChampionEntry& old) { return old.path == key; });
            entries_.push_back(e);
            seen_[key] = mtime;
            changed = true;
            error_.clear();
        } catch (const std::exception& ex) {
            error_ = ex.what();  // e.g. being written: tried again on the next scan
        }
    }
    if (changed)
        std::sort(entries_.begin(), entries_.end(),
                  [](const ChampionEntry& a, const ChampionEntry& b) {
                      return a.generation < b.generation;
                  });
    return changed;
}

std::shared_ptr<const evo::Body> load_champion_body(const std::string& path) {
    const json j = read_json(path);
    try {
        return std::make_shared<const evo::Body>(evo::parse_body(j.at("phenotype"), path));
    } catch (const json::exception& e) {
        throw std::runtime_error(path + ": no phenotype (" + evo::without_json_tags(e.what()) +
                                 ")");
    }
}

std::optional<json> load_champion_controller(const std::string& path) {
    json j = read_json(path);
    if (!j.is_object() || !j.contains("controller")) return std::nullopt;
    return std::move(j["controller"]);
}

}  // namespace bhm::app::gui
