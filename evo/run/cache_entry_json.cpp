#include "evo/run/cache_entry_json.hpp"

#include <array>
#include <stdexcept>

#include "evo/evaluate/exploit_flags.hpp"
#include "evo/evaluate/fitness_json.hpp"
#include "evo/run/report_field.hpp"

namespace bhm::evo {

using nlohmann::json;

namespace {

using Context = CheckpointContext;

constexpr std::array kCacheEntry = {
    hex_field<&CacheEntry::hash, Context>("hash", kNamedCacheEntriesSince, "",
                                          "the phenotype's hash"),
    report_field<&CacheEntry::report, Context>(
        "report", kNamedCacheEntriesSince, "",
        "its FitnessReport (evo/evaluate/fitness_json.hpp), as simulated"),
};

//! Format 4 on: an object read through the table.
CacheEntry named_entry(const json& j, const std::string& where, Context& context) {
    if (j.is_array())
        throw FieldError(where + ": a positional entry in a format " +
                         std::to_string(context.version) + " checkpoint (expected {hash, report})");
    CacheEntry entry;
    read_fields(kCacheEntry, Fields(j, where), entry, context);
    return entry;
}

//! Formats 1 to 3: [hash, diverged, steps, simulated_s, measures, divergence_reason, exploits,
//! behaviour, {ended_early, periodic_residual}]. The 7th element (exploit flags) came with
//! exploit detection, the 8th (the behaviour descriptor) with behaviour descriptors, the 9th with
//! evaluations that end when the motion repeats: older checkpoints have 6 to 8. The form held
//! neither the fitness (scored here under `rules`) nor sim_wall_s (0).
CacheEntry positional_entry(const json& e, const std::string& where, const Fitness& rules) {
    if (!e.is_array() || e.size() < 6 || e.size() > 9)
        throw FieldError(where +
                         ": expected [hash, diverged, steps, simulated_s, measures, reason, "
                         "exploits, behaviour, early end] (formats 1 to 3)");
    auto element = [&](std::size_t k, const char* name) {
        return item(where, k) + " (" + name + ")";
    };
    auto need = [&](bool ok, std::size_t k, const char* name, const char* expected) {
        if (!ok) throw FieldError(element(k, name) + ": expected " + expected);
    };
    need(e[0].is_string(), 0, "hash", "a hex string");
    need(e[1].is_boolean(), 1, "diverged", "true or false");
    need(e[2].is_number_integer(), 2, "steps", "an integer");
    need(e[3].is_number(), 3, "simulated_s", "a number");
    need(e[4].is_array() && e[4].size() == static_cast<std::size_t>(kMeasureCount), 4, "measures",
         "an array of one number per measure");
    need(e[5].is_string(), 5, "divergence_reason", "a string");
    FitnessReport r;
    r.diverged = e[1].get<bool>();
    r.steps = e[2].get<std::int64_t>();
    r.simulated_s = e[3].get<double>();
    for (std::size_t k = 0; k < r.measures.size(); ++k) {
        need(e[4][k].is_number(), 4, "measures", "numbers");
        r.measures[k] = e[4][k].get<double>();
    }
    r.divergence_reason = e[5].get<std::string>();
    if (e.size() >= 7) {
        try {
            r.exploits = exploits_from_json(e[6]);
        } catch (const std::invalid_argument& ex) {
            throw FieldError(item(where, 6) + "." + ex.what());
        }
    }
    if (e.size() >= 8) r.behaviour = behaviour_from_json(e[7], element(7, "behaviour"));
    if (e.size() == 9) {
        const Fields early(e[8], item(where, 8));
        r.ended_early = early.boolean("ended_early");
        r.periodic_residual = early.number("periodic_residual");
    }
    r.fitness = fitness_under(r, rules);
    return {Fields::parse_hex(e[0].get<std::string>(), element(0, "hash")), r};
}

}  // namespace

std::span<const CheckpointFieldOf<CacheEntry>> cache_entry_fields() {
    return kCacheEntry;
}

json cache_to_json(const FitnessCache& cache, const Context& context) {
    json out = json::array();
    for (const auto hash : cache.insertion_order())
        out.push_back(write_fields(kCacheEntry, CacheEntry{hash, *cache.find(hash)}, context));
    return out;
}

void read_cache(const json& array, const std::string& where, const Fitness& rules, Context& context,
                FitnessCache& cache) {
    if (!array.is_array()) throw FieldError(where + ": expected an array");
    for (std::size_t i = 0; i < array.size(); ++i) {
        const CacheEntry entry = context.version >= kNamedCacheEntriesSince
                                     ? named_entry(array[i], item(where, i), context)
                                     : positional_entry(array[i], item(where, i), rules);
        cache.insert(entry.hash, entry.report);
    }
}

}  // namespace bhm::evo
