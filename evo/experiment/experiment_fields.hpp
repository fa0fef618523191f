#pragma once
// The experiment file's field table: each scalar field written once, with its JSON path, where it
// lives in Experiment, its range, unit, the studio's label and a one-line help. Parsing, writing
// and range validation (experiment_io.cpp) and the studio's editor fields and tooltips
// (app/gui/widgets/field_editor.hpp) all walk this table, so they cannot drift apart (MuJoCo's
// mjxmacro.h plays the same part for mjModel). The default of a field is the default member
// initializer of its struct (experiment.hpp, engine/body_spec.hpp), read through the accessor.
// The boundary's faces, frame thicknesses and frame material are rows too. Not in the table,
// because they are not one value: materials' name, library and colour, and the boundary's voxel
// overrides (lists, read and written by experiment_io.cpp). Rules between fields
// (max_hidden_nodes >= min_hidden_nodes) live in field_rules.hpp, which the validator runs and
// field_tooltip quotes.
#include <array>
#include <cmath>
#include <cstdint>
#include <limits>
#include <span>
#include <string>
#include <string_view>

#include "engine/body_spec.hpp"
#include "evo/experiment/experiment.hpp"

namespace bhm::evo {

//! Largest workspace edge in voxels, and most cells: 4 million cells need ~1 GB of engine state.
inline constexpr int kMaxWorkspaceDimension = 255;
inline constexpr long long kMaxWorkspaceCells = 4'000'000;
//! Body layers use one character '1'..'9' per voxel.
inline constexpr int kMaxMaterials = 9;

//! A closed or half-open interval; an infinite end is always open.
struct Range {
    double lo = -std::numeric_limits<double>::infinity();
    double hi = std::numeric_limits<double>::infinity();
    bool lo_open = false;
    bool hi_open = false;
    bool contains(double v) const {
        return std::isfinite(v) && (lo_open ? v > lo : v >= lo) && (hi_open ? v < hi : v <= hi);
    }
    bool bounded() const { return std::isfinite(lo) || std::isfinite(hi); }
};

enum class FieldKind { Text, Number, Integer, Boolean, Choice, Seed, Size3 };

//! One field of an object of type Host (Experiment, or engine::Material for materials[k]).
//! Exactly one accessor is set; it says the kind.
template <class Host>
struct FieldOf {
    const char* path;   //!< JSON path from Host's object: "simulation.settle_s", "poisson_ratio"
    const char* label;  //!< the studio's label
    const char* unit;   //!< SI unit printed after values and ranges; "" for none
    const char* help;   //!< one line: what the field does, with the paper's value where known
    Range range{};      //!< Number, Integer, Size3 (each component)
    const char* note = "";            //!< said after the range in a refusal: "(0 = all cores)"
    const char* format = "%.4g";      //!< the editor's printf format (Number)
    std::string& (*text)(Host&) = nullptr;
    double& (*number)(Host&) = nullptr;
    int& (*integer)(Host&) = nullptr;
    bool& (*boolean)(Host&) = nullptr;
    int (*get_choice)(const Host&) = nullptr;
    void (*set_choice)(Host&, int) = nullptr;
    std::span<const char* const> choices{};
    std::uint64_t& (*seed)(Host&) = nullptr;
    std::array<int, 3>& (*size3)(Host&) = nullptr;

    FieldKind kind() const {
        if (text) return FieldKind::Text;
        if (number) return FieldKind::Number;
        if (integer) return FieldKind::Integer;
        if (boolean) return FieldKind::Boolean;
        if (get_choice) return FieldKind::Choice;
        if (seed) return FieldKind::Seed;
        return FieldKind::Size3;
    }
    //! The JSON path of the object holding the field ("" = Host's own) and the field's key.
    std::string_view parent() const {
        const std::string_view p(path);
        const auto dot = p.rfind('.');
        return dot == std::string_view::npos ? std::string_view() : p.substr(0, dot);
    }
    std::string_view key() const {
        const std::string_view p(path);
        const auto dot = p.rfind('.');
        return dot == std::string_view::npos ? p : p.substr(dot + 1);
    }
};

using ExperimentField = FieldOf<Experiment>;
using MaterialField = FieldOf<engine::Material>;  //!< fields of materials[k]

//! Every scalar field of the experiment file, in the file's order.
std::span<const ExperimentField> experiment_fields();
//! The physical fields of one material (materials[k].youngs_modulus_pa, ...).
std::span<const MaterialField> material_fields();
//! The field with this JSON path, or nullptr.
const ExperimentField* find_experiment_field(std::string_view path);
const MaterialField* find_material_field(std::string_view key);

//! A bound as messages print it: 100000, 0.49, 1e6, 1e-6.
std::string range_number(double x);
//! "[0, 10000]", "(0, 1e6]", "[0, inf)".
std::string range_text(const Range& range);
//! "must be in [0, 10000] s" and the field's note: what a refusal says.
template <class Host>
std::string range_message(const FieldOf<Host>& field);
//! The studio's tooltip: help, range and unit (or the choices), the rules on the field
//! (field_rules.hpp), and the default.
template <class Host>
std::string field_tooltip(const FieldOf<Host>& field);
//! The value as text ("0.9", "true", "afpo", "[8, 8, 7]").
template <class Host>
std::string field_value_text(const FieldOf<Host>& field, const Host& host);

}  // namespace bhm::evo
