#pragma once
// The field-table row of a member holding a FitnessReport: written and read through
// report_to_json / report_from_json (evo/evaluate/fitness_json.hpp), the report's one
// serialisation, wherever a run file keeps one (a population member, a fitness cache entry).
#include "evo/evaluate/fitness_json.hpp"
#include "evo/run/json_schema.hpp"

namespace bhm::evo {

template <auto M, class Context>
void write_report_member(const HostOf<M>& host, const char* key, nlohmann::json& out,
                         const Context&) {
    out[key] = report_to_json(host.*M);
}

template <auto M, class Context>
void read_report_member(const Fields& object, const JsonField<HostOf<M>, Context>& field,
                        HostOf<M>& host, Context&) {
    host.*M = report_from_json(object.at(field.key), object.join(field.key));
}

template <auto M, class Context>
constexpr JsonField<HostOf<M>, Context> report_field(const char* key, int since, const char* when,
                                                     const char* description) {
    return {key,
            "report",
            since,
            when,
            description,
            write_report_member<M, Context>,
            read_report_member<M, Context>};
}

}  // namespace bhm::evo
