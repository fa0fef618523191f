#pragma once
// The material library (assets/materials/, docs/materials-format.md): one JSON file per material,
// each value with the source it came from and the range of values reported, read strictly (every
// problem as "file:field: message"). An experiment's material slot names an entry with
// "library": "<id>" (the file's name without .json) and takes the values it does not give itself.
#include <array>
#include <optional>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "evo/experiment/experiment.hpp"
#include "evo/experiment/experiment_io.hpp"

namespace bhm::evo {

//! One property of a library material: the value the engine is given, where it came from, and
//! the range reported in the literature (which may reach past what the engine admits, e.g. nu 0.5).
struct SourcedValue {
    double value = 0.0;
    std::optional<std::array<double, 2>> range;  //!< [low, high] reported; absent: one value found
    std::string source;  //!< citation: paper (authors, journal, year) or datasheet
    std::string note;    //!< how the value was derived, or why it differs from the range
    bool operator==(const SourcedValue&) const = default;
};

struct LibraryMaterial {
    std::string id;    //!< file name without .json, e.g. "ecoflex-00-30"
    std::string file;  //!< the file it was read from
    std::string name;  //!< e.g. "Ecoflex 00-30 (Smooth-On)"
    std::string category;  //!< one of kLibraryCategories
    std::string description;
    std::string engine_note;  //!< what the engine does with it (required)
    SourcedValue youngs_modulus_pa;  //!< required
    //! Values that could not be sourced are absent: the slot keeps its own.
    std::optional<SourcedValue> poisson_ratio, density_kg_m3, static_friction, dynamic_friction;
    //! Active tissue ("active" object): contraction strain (linear, fraction) and frequency (Hz).
    bool active = false;
    std::optional<SourcedValue> contraction_strain, frequency_hz;
    //! Active tissue's twitch: the activation's rise and decay time constants (s) of the muscle
    //! model (engine/muscle.hpp), where a source gives them (issue 43).
    std::optional<SourcedValue> rise_s, decay_s;
    //! Measured quantities the engine does not take as input but a slot's values are judged or
    //! derived by (docs/materials-format.md): the active stress (Pa) a tissue developed, and the
    //! twitch-to-tetanus force ratio that, with a time to peak, gives rise_s.
    std::optional<SourcedValue> active_stress_pa, twitch_tetanus_ratio;
    std::optional<std::array<float, 3>> color;
    bool operator==(const LibraryMaterial&) const = default;
};

inline constexpr std::array<const char*, 4> kLibraryCategories = {"silicone", "thermoplastic",
                                                                  "tissue", "hydrogel"};

//! A library file that did not read as a material. Only an experiment naming its id fails (the
//! error names the file); the rest of the library stays usable (issue 41 R10).
struct DamagedLibraryFile {
    std::string id;                 //!< file name without .json
    std::string file;               //!< its path
    std::vector<Problem> problems;  //!< every problem, as `bhm validate` reports them
};

struct MaterialLibrary {
    std::string dir;
    std::vector<LibraryMaterial> materials;  //!< sorted by id
    std::vector<DamagedLibraryFile> damaged;  //!< sorted by id
    //! Entries of the folder that were not read, and never opened (a FIFO would block an open): a
    //! folder, a named pipe, a socket or device, a symbolic link to nothing. Field "(file)", the
    //! message says what it is.
    std::vector<Problem> skipped;
    const LibraryMaterial* find(const std::string& id) const;
    const DamagedLibraryFile* find_damaged(const std::string& id) const;
    std::vector<std::string> ids() const;
    //! One line per skipped entry and per damaged file (its first problem), for wherever the
    //! library is listed or used: `bhm materials`, an experiment filled from it, the studio.
    std::vector<std::string> warnings() const;
};

//! The library folder: $BHM_MATERIALS_DIR when set, else <exe>/../share/bhm/materials when it
//! exists, else the source tree's assets/materials. May not exist.
std::string default_material_library_dir();

//! Reads every regular *.json of dir. A file that does not read goes to `damaged`, an entry that
//! is not a regular file to `skipped`; throws ValidationError only when dir is not a listable
//! folder or holds no material files at all.
MaterialLibrary load_material_library(const std::string& dir);

//! One file's entry (id = file name without .json); throws ValidationError.
LibraryMaterial load_library_material(const std::string& path);
LibraryMaterial parse_library_material(const nlohmann::json& json, const std::string& file_label,
                                       const std::string& id);

//! What filling a slot from the library sets: E, and nu, density, friction, colour where the
//! library has them. For active tissue, by the slot's actuation_model: a sine slot gets cte_per_c =
//! strain / temperature_amplitude_c (the engine's actuation strain is cte x amplitude,
//! docs/materials-format.md); a muscle slot gets cte_per_c 0 and the muscle model's contraction
//! strain, rise and decay times and frequency where the library has them. The name is set when the
//! slot has none. entry.library = m.id.
void apply_library_material(const LibraryMaterial& m, double temperature_amplitude_c,
                            MaterialEntry& entry);

//! "1.18e+05 Pa (range 6e4-1.3e5) - Smooth-On ...": one line per property, for `bhm materials`
//! and the studio's picker.
std::string describe_library_material(const LibraryMaterial& m);

}  // namespace bhm::evo
