#pragma once
// The field tables of the parts a checkpoint holds (json_schema.hpp): a member of the population
// (and the champion), a history row with its novelty figures, NEAT's state and species, the
// novelty archive. The payload's own table (checkpoint_schema.cpp) holds them as rows; the
// checkpoint's writer and reader walk them, and docs/evolution.md's table is generated from them.
#include <span>
#include <string>

#include "evo/run/checkpoint_schema.hpp"

namespace bhm::evo {

//! A member of the population; the genome is read before the phenotype hash it is checked against.
std::span<const CheckpointFieldOf<Individual>> individual_fields();
std::span<const CheckpointFieldOf<HistoryRow>> history_row_fields();
std::span<const CheckpointFieldOf<NoveltyRow>> novelty_row_fields();
std::span<const CheckpointFieldOf<NeatState>> neat_state_fields();
std::span<const CheckpointFieldOf<NeatSpecies>> neat_species_fields();
std::span<const CheckpointFieldOf<NoveltyArchive>> novelty_archive_fields();
std::span<const CheckpointFieldOf<ChampionRecord>> champion_fields();

//! An object read by `fields` into a fresh T; "WHERE.field" in errors.
template <class T>
T read_part(std::span<const CheckpointFieldOf<T>> fields, const nlohmann::json& j,
            const std::string& where, CheckpointContext& context) {
    T value{};
    read_fields(fields, Fields(j, where), value, context);
    return value;
}

}  // namespace bhm::evo
