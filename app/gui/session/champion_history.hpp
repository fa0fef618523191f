#pragma once
// Every generation's champion of a run (the champions/gen-NNNNN.json files `bhm evolve` and the
// studio write): listed for the Champions tab, re-scanned as the run grows, each file parsed once.
#include <chrono>
#include <cstdint>
#include <map>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include <filesystem>

#include <nlohmann/json.hpp>

#include "evo/evaluate/exploit_flags.hpp"
#include "evo/experiment/experiment.hpp"

namespace bhm::app::gui {

struct ChampionEntry {
    int generation = 0;  //!< generation_found
    std::int64_t id = 0;
    double fitness = 0.0;
    evo::FitnessMeasure measure = evo::FitnessMeasure::ComFinal3d;
    int voxels = 0, active_voxels = 0;
    evo::ExploitReport exploits;
    std::string path;
};

class ChampionHistory {
  public:
    //! Lists run_dir/champions (at most twice a second; new files parsed once). Returns true when
    //! the list changed. A different run_dir starts over.
    bool refresh(const std::string& run_dir);
    const std::vector<ChampionEntry>& entries() const { return entries_; }  //!< by generation
    const std::string& error() const { return error_; }

  private:
    std::string dir_;
    std::vector<ChampionEntry> entries_;
    std::map<std::string, std::filesystem::file_time_type> seen_;
    std::chrono::steady_clock::time_point checked_{};
    std::string error_;
};

//! The framed body of a champion file (its phenotype). Throws std::runtime_error naming the file.
std::shared_ptr<const evo::Body> load_champion_body(const std::string& path);
//! The champion's controller as a controller file's object (its "controller": a run of
//! evolution.controller coevolve or fixed_body writes one; issue 44); nullopt when it has none.
//! Throws std::runtime_error naming the file when it cannot be read.
std::optional<nlohmann::json> load_champion_controller(const std::string& path);

}  // namespace bhm::app::gui
