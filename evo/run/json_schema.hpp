#pragma once
// A JSON object's schema as one table of fields (issue 41): each row names the field, its type,
// the format version that first may hold it, when it is written, what it means, and the two
// functions that write it from its C++ value and read it back. A file's writer and reader both walk
// the table (write_fields, read_fields) and its documentation is generated from it
// (describe_fields, schema_markdown), so the three cannot drift apart. The model is the
// experiment's field table (evo/experiment/experiment_fields.hpp), itself after MuJoCo's
// mjxmacro.h.
//
// A row of a plain member (an integer, a number, a boolean or a string of Host) is made by
// member_field<&Host::member, Context>(key, since, when, description); others name their functions.
// A row whose `when` is not empty, or that a file of an older format (Context::version < since)
// may lack, is optional on reading: the member keeps its default when the field is absent.
#include <algorithm>
#include <cstdint>
#include <span>
#include <string>
#include <string_view>
#include <type_traits>
#include <vector>

#include <nlohmann/json.hpp>

#include "evo/experiment/json_fields.hpp"

namespace bhm::evo {

//! One row of a schema as the docs print it: the field's whole JSON path ("history[].species",
//! "[]" for every element of an array), its type, since, when ("" for always) and meaning.
struct SchemaLine {
    std::string path;
    std::string type;
    int since = 1;
    std::string when;
    std::string description;
};

//! One field of the JSON object that a Host is written as. Context carries what writing and
//! reading need beyond the object itself (the file's format version as `version`, the experiment
//! a section is read against, ...).
template <class Host, class Context>
struct JsonField {
    const char* key;
    //! "string", "hex" (up to 16 lowercase hex digits), "integer", "number", "boolean",
    //! "object", "objects" (an array of objects with rows of their own), "array", "object or
    //! null", or a part with its own schema named by where it is described ("report", ...).
    const char* type;
    int since;                //!< the first format version that may hold it
    const char* when;         //!< "" when every object of that version holds it
    const char* description;  //!< one line
    //! Sets out[key] from host, or leaves it out where the field does not apply.
    void (*write)(const Host& host, const char* key, nlohmann::json& out, const Context& context);
    //! Reads the field of `object` into host; nullptr: written for people and other programs
    //! (the Python module), not read back.
    void (*read)(const Fields& object, const JsonField& field, Host& host, Context& context);
    //! The rows of the object(s) the field holds, for the docs; nullptr for none.
    void (*describe)(const SchemaLine& self, std::vector<SchemaLine>& out) = nullptr;

    //! Whether reading may find it absent (see the top of this file).
    bool may_be_absent(const Context& context) const {
        return *when != '\0' || context.version < since;
    }
    //! Whether it is absent from `object` where it may be: then it is not read.
    bool skipped(const Fields& object, const Context& context) const {
        return !object.has(key) && may_be_absent(context);
    }
};

//! The object `fields` write for host.
template <class Rows, class Host, class Context>
nlohmann::json write_fields(const Rows& fields, const Host& host, const Context& context) {
    nlohmann::json out = nlohmann::json::object();
    for (const auto& field : fields)
        field.write(host, field.key, out, context);
    return out;
}

//! Reads each field of `fields` from `object` into host, in the table's order (a row may use what
//! the rows before it read). Throws FieldError naming the first field missing or wrong.
template <class Rows, class Host, class Context>
void read_fields(const Rows& fields, const Fields& object, Host& host, Context& context) {
    for (const auto& field : fields)
        if (field.read) field.read(object, field, host, context);
}

//! The lines of `fields` under `prefix`: each inherits its parent's since (the later of the two)
//! and when (where it has none of its own).
template <class Rows>
void describe_fields(const Rows& fields, const std::string& prefix, const SchemaLine* parent,
                     std::vector<SchemaLine>& out) {
    for (const auto& field : fields) {
        SchemaLine line{prefix + field.key, field.type, field.since, field.when, field.description};
        if (parent) {
            line.since = std::max(line.since, parent->since);
            if (line.when.empty()) line.when = parent->when;
        }
        out.push_back(line);
        if (field.describe) field.describe(line, out);
    }
}

//! A `describe` for a field holding one object (path.key) or an array of them (path[].key) whose
//! rows RowsOf() returns.
template <auto RowsOf>
void describe_object(const SchemaLine& self, std::vector<SchemaLine>& out) {
    describe_fields(RowsOf(), self.path + (self.type == "objects" ? "[]." : "."), &self, out);
}

//! The lines as a Markdown table (field, type, since, when, meaning), one row each; without the
//! since column for a file that has no format versions.
std::string schema_markdown(std::span<const SchemaLine> lines, bool with_since = true);
//! The line with this path, or nullptr.
const SchemaLine* find_schema_line(std::span<const SchemaLine> lines, std::string_view path);

// --- rows of plain members ----------------------------------------------------------------------

template <class T>
struct MemberPointer;
template <class H, class V>
struct MemberPointer<V H::*> {
    using Host = H;
    using Value = V;
};
template <auto M>
using HostOf = typename MemberPointer<decltype(M)>::Host;
template <auto M>
using ValueOf = typename MemberPointer<decltype(M)>::Value;

//! The schema's type of a member's value.
template <class V>
constexpr const char* json_type_of() {
    if constexpr (std::is_same_v<V, bool>)
        return "boolean";
    else if constexpr (std::is_integral_v<V>)
        return "integer";
    else if constexpr (std::is_floating_point_v<V>)
        return "number";
    else
        return "string";
}

template <auto M, class Context>
void write_member(const HostOf<M>& host, const char* key, nlohmann::json& out, const Context&) {
    out[key] = host.*M;
}

template <auto M, class Context>
void read_member(const Fields& object, const JsonField<HostOf<M>, Context>& field, HostOf<M>& host,
                 Context& context) {
    using V = ValueOf<M>;
    if (field.skipped(object, context)) return;
    if constexpr (std::is_same_v<V, bool>)
        host.*M = object.boolean(field.key);
    else if constexpr (std::is_unsigned_v<V>)
        host.*M = static_cast<V>(object.unsigned64(field.key));
    else if constexpr (std::is_integral_v<V>)
        host.*M = static_cast<V>(object.integer(field.key));
    else if constexpr (std::is_floating_point_v<V>)
        host.*M = object.number(field.key);
    else
        host.*M = object.string(field.key);
}

//! The row of a plain member: written as its value, read as its type.
template <auto M, class Context>
constexpr JsonField<HostOf<M>, Context> member_field(const char* key, int since, const char* when,
                                                     const char* description) {
    return {key,
            json_type_of<ValueOf<M>>(),
            since,
            when,
            description,
            write_member<M, Context>,
            read_member<M, Context>};
}

//! "%016x": how a 64-bit hash or seed is written where the schema says "hex".
std::string hex64_text(std::uint64_t value);

template <auto M, class Context>
void write_hex_member(const HostOf<M>& host, const char* key, nlohmann::json& out, const Context&) {
    out[key] = hex64_text(host.*M);
}

template <auto M, class Context>
void read_hex_member(const Fields& object, const JsonField<HostOf<M>, Context>& field,
                     HostOf<M>& host, Context& context) {
    if (field.skipped(object, context)) return;
    host.*M = object.hex64(field.key);
}

//! The row of a 64-bit member written as hex text.
template <auto M, class Context>
constexpr JsonField<HostOf<M>, Context> hex_field(const char* key, int since, const char* when,
                                                  const char* description) {
    return {key,
            "hex",
            since,
            when,
            description,
            write_hex_member<M, Context>,
            read_hex_member<M, Context>};
}

// --- arrays of objects --------------------------------------------------------------------------

//! items as an array of objects, each written by the rows RowsOf() returns.
template <auto RowsOf, class Items, class Context>
nlohmann::json write_objects(const Items& items, const Context& context) {
    nlohmann::json out = nlohmann::json::array();
    for (const auto& item : items)
        out.push_back(write_fields(RowsOf(), item, context));
    return out;
}

//! An array of objects read by the rows RowsOf() returns; element i is named "WHERE[i]".
template <auto RowsOf, class T, class Context>
std::vector<T> read_objects(const nlohmann::json& array, const std::string& where,
                            Context& context) {
    if (!array.is_array()) throw FieldError(where + ": expected an array");
    std::vector<T> out;
    out.reserve(array.size());
    for (std::size_t i = 0; i < array.size(); ++i) {
        T value{};
        read_fields(RowsOf(), Fields(array[i], item(where, i)), value, context);
        out.push_back(std::move(value));
    }
    return out;
}

}  // namespace bhm::evo
