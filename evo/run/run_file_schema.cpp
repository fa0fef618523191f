#include "evo/run/run_file_schema.hpp"

#include <algorithm>
#include <array>
#include <filesystem>
#include <stdexcept>
#include <vector>

#include "evo/evaluate/fitness_json.hpp"
#include "evo/experiment/experiment_io.hpp"
#include "evo/genome/controller.hpp"
#include "evo/genome/genome.hpp"
#include "evo/run/rule_change_json.hpp"

namespace bhm::evo {

using nlohmann::json;

namespace {

using Context = RunFileContext;

// --- run.json ----------------------------------------------------------------------------------

using RunField = RunFileFieldOf<RunInfo>;

void write_started(const RunInfo& info, const char* key, json& out, const Context&) {
    out[key] = experiment_to_json(info.started);
}
void read_started(const Fields& f, const RunField& field, RunInfo& info, Context& context) {
    // Its ValidationError names the file and the field.
    info.started = parse_experiment(f.at(field.key), context.path + ":" + field.key);
}

void write_rule_changes(const RunInfo& info, const char* key, json& out, const Context&) {
    out[key] = rule_changes_to_json(info.rule_changes, info.started);
}
void read_rule_changes(const Fields& f, const RunField& field, RunInfo& info, Context& context) {
    if (field.skipped(f, context)) return;
    info.rule_changes = rule_changes_from_json(f.at(field.key), info.started, field.key);
}

constexpr std::array kRunInfoFields = {
    member_field<&RunInfo::bhm_version, Context>("bhm_version", 1, "", "the bhm that started it"),
    member_field<&RunInfo::seed, Context>("seed", 1, "",
                                          "the run's seed (a number here, hex in the checkpoint)"),
    RunField{"experiment", "experiment", 1, "",
             "the experiment as the run was started, as the experiment file writes it",
             write_started, read_started},
    RunField{"rule_changes", "objects", 1,
             "absent in run.json files written before rule changes were recorded",
             "every rule change in order, as the checkpoint holds them (which a reader trusts "
             "where the two differ: run_directory.hpp)",
             write_rule_changes, read_rule_changes, describe_object<rule_change_fields>},
};

// --- champion.json -----------------------------------------------------------------------------

using ChampionField = RunFileFieldOf<ChampionRecord>;

void write_experiment_name(const ChampionRecord&, const char* key, json& out,
                           const Context& context) {
    out[key] = context.experiment->name;
}
void write_measure(const ChampionRecord&, const char* key, json& out, const Context& context) {
    out[key] = kFitnessNames[static_cast<std::size_t>(context.experiment->fitness.measure)];
}
void read_measure(const Fields& f, const ChampionField& field, ChampionRecord&, Context& context) {
    const std::string name = f.string(field.key);
    const auto known = std::find(kFitnessNames.begin(), kFitnessNames.end(), name);
    if (known == kFitnessNames.end()) f.fail(field.key, "unknown measure '" + name + "'");
    context.measure = static_cast<FitnessMeasure>(known - kFitnessNames.begin());
}

//! The row of a plain member M of a part of the champion's individual (its report or phenotype).
template <auto Part, auto M>
void write_part_member(const ChampionRecord& c, const char* key, json& out, const Context&) {
    out[key] = c.individual.*Part.*M;
}
template <auto Part, auto M>
void read_part_member(const Fields& f, const ChampionField& field, ChampionRecord& c, Context&) {
    using V = ValueOf<M>;
    if constexpr (std::is_floating_point_v<V>)
        c.individual.*Part.*M = f.number(field.key);
    else
        c.individual.*Part.*M = static_cast<V>(f.integer(field.key));
}
template <auto Part, auto M>
constexpr ChampionField part_field(const char* key, const char* description) {
    return {key,
            json_type_of<ValueOf<M>>(),
            1,
            "",
            description,
            write_part_member<Part, M>,
            read_part_member<Part, M>};
}
template <auto M>
void write_individual_member(const ChampionRecord& c, const char* key, json& out, const Context&) {
    out[key] = c.individual.*M;
}
template <auto M>
void read_individual_member(const Fields& f, const ChampionField& field, ChampionRecord& c,
                            Context&) {
    c.individual.*M = static_cast<ValueOf<M>>(f.integer(field.key));
}
//! The row of an integer member M of the champion's individual.
template <auto M>
constexpr ChampionField individual_field(const char* key, const char* description) {
    return {
        key, "integer", 1, "", description, write_individual_member<M>, read_individual_member<M>};
}

void write_report(const ChampionRecord& c, const char* key, json& out, const Context&) {
    out[key] = report_to_json(c.individual.report);
}
void read_report(const Fields& f, const ChampionField& field, ChampionRecord& c, Context&) {
    c.individual.report = report_from_json(f.at(field.key), field.key);
}

void write_phenotype(const ChampionRecord& c, const char* key, json& out, const Context&) {
    out[key] = body_to_json(c.individual.phenotype.body);
}
//! The body, checked against the experiment: a champion of another experiment (files mixed up,
//! a damaged run.json) would export materials and cells that experiment does not define.
void read_phenotype(const Fields& f, const ChampionField& field, ChampionRecord& c,
                    Context& context) {
    if (!context.experiment) {  // a summary
        f.at(field.key);        // every champion file holds one
        return;
    }
    const std::string label = context.path + " (phenotype)";
    Body body = parse_body(f.at(field.key), label);
    const auto problems = validate_body_against(body, *context.experiment, label);
    if (!problems.empty())
        throw std::runtime_error(problems.front().to_string() + " (the champion does not fit " +
                                 (std::filesystem::path(context.run_dir) / kRunInfoFile).string() +
                                 "'s experiment)");
    c.individual.phenotype.body = std::move(body);
}

void write_genome(const ChampionRecord& c, const char* key, json& out, const Context& context) {
    const bool fibres = context.experiment && context.experiment->evolution.cppn.fibre_outputs;
    out[key] = genome_to_json(c.individual.genome, fibres ? 3 : 0);
}
void read_genome(const Fields& f, const ChampionField& field, ChampionRecord& c, Context& context) {
    if (!context.experiment) return;  // a summary
    try {
        c.individual.genome =
            genome_from_json(f.at(field.key), context.experiment->evolution.cppn.weight_range);
    } catch (const std::invalid_argument& e) {
        throw FieldError(e.what());  // "genome.field: message"
    }
}

//! The champion's controller CPPN as a controller file (evo/genome/controller.hpp): the genome
//! itself in a fixed_body run (with its substrate's settings in a HyperNEAT run,
//! docs/hyperneat.md), the individual's controller in a coevolve run; absent otherwise.
void write_controller(const ChampionRecord& c, const char* key, json& out, const Context& context) {
    if (!context.experiment) return;
    const ControllerMode mode = context.experiment->evolution.controller.mode;
    if (mode == ControllerMode::FixedBody)
        out[key] =
            context.experiment->evolution.algorithm == Algorithm::HyperNeat
                ? controller_to_json(c.individual.genome, context.experiment->evolution.hyperneat)
                : controller_to_json(c.individual.genome);
    if (mode == ControllerMode::Coevolve) out[key] = controller_to_json(c.individual.controller);
}
void read_controller(const Fields& f, const ChampionField& field, ChampionRecord& c,
                     Context& context) {
    if (!context.experiment || !f.has(field.key)) return;
    if (context.experiment->evolution.controller.mode != ControllerMode::Coevolve) return;
    try {
        c.individual.controller =
            controller_from_json(f.at(field.key), context.experiment->evolution.cppn.weight_range);
    } catch (const std::invalid_argument& e) {
        throw FieldError(e.what());
    }
}

// The body first: a champion of another experiment is refused as such before anything else.
constexpr std::array kChampionFields = {
    ChampionField{"phenotype", "body", 1, "",
                  "the framed, workspace-sized body, as a body file (docs/experiment-format.md)",
                  write_phenotype, read_phenotype},
    ChampionField{"experiment", "string", 1, "", "the experiment's name (not read back)",
                  write_experiment_name, nullptr},
    ChampionField{"measure", "string", 1, "", "the fitness measure its fitness is of",
                  write_measure, read_measure},
    member_field<&ChampionRecord::generation_found, Context>("generation_found", 1, "",
                                                             "the generation that found it"),
    individual_field<&Individual::id>("id", "its id"),
    individual_field<&Individual::parent_id>("parent_id", "its parent's id (-1: none)"),
    individual_field<&Individual::age>("age", "AFPO age"),
    ChampionField{"report", "report", 1, "", "its FitnessReport (evo/evaluate/fitness_json.hpp)",
                  write_report, read_report},
    part_field<&Individual::report, &FitnessReport::fitness>(
        "fitness", "its fitness under the rules in force when it was found (the report's)"),
    part_field<&Individual::phenotype, &Phenotype::voxels>("voxels", "filled cells of its body"),
    part_field<&Individual::phenotype, &Phenotype::active_voxels>("active_voxels",
                                                                  "cells with an active material"),
    ChampionField{"genome", "genome", 1, "",
                  "the CPPN (evo/genome/genome.hpp); the controller's in a fixed_body run",
                  write_genome, read_genome},
    ChampionField{
        "controller", "controller", 1, "evolution.controller fixed_body or coevolve",
        "its controller as a controller file (controller.json; evo/genome/controller.hpp)",
        write_controller, read_controller},
};

}  // namespace

std::span<const RunFileFieldOf<RunInfo>> run_info_fields() {
    return kRunInfoFields;
}

std::span<const RunFileFieldOf<ChampionRecord>> champion_file_fields() {
    return kChampionFields;
}

std::string run_file_schema_markdown(std::string_view file) {
    std::vector<SchemaLine> lines;
    if (file == kRunInfoFile) describe_fields(kRunInfoFields, "", nullptr, lines);
    if (file == kChampionFile) describe_fields(kChampionFields, "", nullptr, lines);
    return schema_markdown(lines, false);
}

}  // namespace bhm::evo
