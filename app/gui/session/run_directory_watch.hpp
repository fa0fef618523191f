#pragma once
// Viewing a run directory written by `bhm evolve` (also one still growing elsewhere): the fitness
// history, the champion and the population (population.csv: each member's fitness, age and
// volume, without its body; the champion's body is champion.json's) are re-read when their files'
// modification times change, and turned into the same EvolutionSnapshot the live session
// publishes, so every panel works on both.
#include <cstdint>
#include <filesystem>
#include <map>
#include <memory>
#include <string>

#include "app/gui/session/evolution_snapshot.hpp"

namespace bhm::app::gui {

class RunDirectoryWatch {
  public:
    //! Opens a run directory; throws std::runtime_error naming the folder when it is not one.
    void open(const std::string& run_dir);
    void close();
    bool is_open() const { return !dir_.empty(); }
    const std::string& dir() const { return dir_; }

    //! Stats the files (cheap) and re-reads those whose modification time changed. Returns true
    //! when the snapshot changed. Errors (a file half-written by the other process) keep the last
    //! good snapshot and set error().
    bool refresh();
    std::shared_ptr<const EvolutionSnapshot> snapshot() const { return snapshot_; }
    //! Gives the population's members their bodies, developed from the run's checkpoint (the
    //! genomes are there; population.csv has none), so a click on any of them can show it. Reads
    //! the whole checkpoint, synchronously: called for a click on a member without a body. The
    //! bodies are kept for the members that stay in later generations. Returns true when the
    //! snapshot changed; a checkpoint that cannot be read sets error() and changes nothing.
    bool load_bodies();
    const std::string& error() const { return error_; }
    int reloads() const { return reloads_; }  //!< how many times files were re-read

  private:
    std::string dir_;
    std::filesystem::file_time_type fitness_mtime_{}, champion_mtime_{}, experiment_mtime_{},
        population_mtime_{};
    std::shared_ptr<const EvolutionSnapshot> snapshot_;
    std::string error_;
    std::string fitness_problem_;     //!< a row of fitness.csv that could not be read
    std::string population_problem_;  //!< population.csv, or a row of it, that could not be read
    int reloads_ = 0;
    std::map<std::int64_t, std::shared_ptr<const evo::Body>> bodies_;  //!< by id (load_bodies)
    std::map<std::int64_t, std::uint64_t> hashes_;                     //!< their phenotype hashes
};

}  // namespace bhm::app::gui
