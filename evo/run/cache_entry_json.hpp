#pragma once
// The fitness cache as a checkpoint holds it, oldest entry first. From format 4 each entry is an
// object {hash, report} (cache_entry_fields, a field table: json_schema.hpp), the report in its one
// form (fitness_json.hpp) exactly as simulated. Formats 1 to 3 held positional arrays, still read:
// the checkpoint's format_version says which form its cache holds.
#include <cstdint>
#include <span>
#include <string>

#include <nlohmann/json.hpp>

#include "evo/evaluate/fitness_cache.hpp"
#include "evo/run/checkpoint_schema.hpp"

namespace bhm::evo {

//! One entry: the phenotype's hash and its result.
struct CacheEntry {
    std::uint64_t hash = 0;
    FitnessReport report;
};

std::span<const CheckpointFieldOf<CacheEntry>> cache_entry_fields();

//! Every entry of `cache`, oldest first, in the form of this build's format.
nlohmann::json cache_to_json(const FitnessCache& cache, const CheckpointContext& context);
//! Inserts each entry of `array` (the form of context.version) into `cache`, oldest first. The
//! positional form held no fitness: it is scored under `rules`. Throws FieldError naming
//! "WHERE[i]" and the field or element.
void read_cache(const nlohmann::json& array, const std::string& where, const Fitness& rules,
                CheckpointContext& context, FitnessCache& cache);

}  // namespace bhm::evo
