#include "evo/experiment/field_io.hpp"

#include <algorithm>
#include <cstdint>
#include <string_view>

namespace bhm::evo {

namespace {

using nlohmann::json;

// Integers are read as long long, checked to fit an int here; the table's range comes later.
constexpr long long kBig = 1'000'000'000LL;

// "a.b"; either may be empty ("" + "b" = "b", "a" + "" = "a").
std::string join(std::string_view a, std::string_view b) {
    return b.empty() ? std::string(a) : JsonReader::join(std::string(a), std::string(b));
}

// The keys an object at `parent` may hold: the table's fields and sub-objects there, and extras.
template <class Host>
std::vector<std::string> known_keys(std::span<const FieldOf<Host>> fields,
                                    const std::string& parent, const ExtraKeys& extra) {
    std::vector<std::string> keys;
    auto add = [&](std::string key) {
        if (std::find(keys.begin(), keys.end(), key) == keys.end()) keys.push_back(std::move(key));
    };
    for (const auto& f : fields) {
        const std::string_view p = f.parent();
        if (p == parent) {
            add(std::string(f.key()));
        } else if (parent.empty() ||
                   (p.size() > parent.size() && p.starts_with(parent) && p[parent.size()] == '.')) {
            const std::string_view rest = parent.empty() ? p : p.substr(parent.size() + 1);
            add(std::string(rest.substr(0, rest.find('.'))));
        }
    }
    if (auto it = extra.find(parent); it != extra.end())
        for (const auto& key : it->second)
            add(key);
    return keys;
}

std::vector<std::string> names_of(std::span<const char* const> choices) {
    return {choices.begin(), choices.end()};
}

void read_seed(JsonReader& r, const json& obj, const std::string& key, const std::string& field,
               std::uint64_t& out) {
    const auto it = obj.find(key);
    if (it == obj.end()) return;
    if (it->is_number_unsigned())
        out = it->get<std::uint64_t>();
    else if (it->is_number_integer())
        r.problem(field, "must be a non-negative integer");
    else
        r.problem(field, "expected an integer, got " + JsonReader::type_name(*it));
}

}  // namespace

template <class Host>
void read_fields(JsonReader& r, const json& root, const std::string& root_path,
                 std::span<const FieldOf<Host>> fields, Host& host, const ExtraKeys& extra_keys) {
    // Objects by path relative to root, nullptr when absent or not an object (reported once).
    std::map<std::string, const json*, std::less<>> objects;
    objects[""] = &root;
    r.check_keys(root, root_path, known_keys(fields, "", extra_keys));
    auto object_at = [&](auto& self, std::string_view parent) -> const json* {
        if (auto it = objects.find(parent); it != objects.end()) return it->second;
        const auto dot = parent.rfind('.');
        const std::string_view above = dot == std::string_view::npos ? "" : parent.substr(0, dot);
        const std::string name(dot == std::string_view::npos ? parent : parent.substr(dot + 1));
        const json* outer = self(self, above);
        const json* o = outer ? r.object(*outer, name, join(root_path, above)) : nullptr;
        if (o)
            r.check_keys(*o, join(root_path, parent),
                         known_keys(fields, std::string(parent), extra_keys));
        objects.emplace(std::string(parent), o);
        return o;
    };
    for (const auto& f : fields) {
        const json* o = object_at(object_at, f.parent());
        if (!o) continue;
        const std::string key(f.key()), opath = join(root_path, f.parent());
        switch (f.kind()) {
            case FieldKind::Text:
                f.text(host) = r.string(*o, key, opath, f.text(host));
                break;
            case FieldKind::Number:
                f.number(host) = r.number(*o, key, opath, f.number(host));
                break;
            case FieldKind::Integer:
                f.integer(host) =
                    static_cast<int>(r.integer(*o, key, opath, f.integer(host), -kBig, kBig));
                break;
            case FieldKind::Boolean:
                f.boolean(host) = r.boolean(*o, key, opath, f.boolean(host));
                break;
            case FieldKind::Choice:
                f.set_choice(host,
                             r.choice(*o, key, opath, names_of(f.choices), f.get_choice(host)));
                break;
            case FieldKind::Seed:
                read_seed(r, *o, key, join(opath, key), f.seed(host));
                break;
            case FieldKind::Size3:
                r.array3(*o, key, opath, f.size3(host));
                break;
        }
    }
}

template <class Host>
void write_fields(const Host& host, std::span<const FieldOf<Host>> fields, json& out) {
    Host& h = const_cast<Host&>(host);  // the accessors are shared with the readers; read only here
    for (const auto& f : fields) {
        json* o = &out;
        std::string_view parent = f.parent();
        while (!parent.empty()) {
            const auto dot = parent.find('.');
            o = &(*o)[std::string(parent.substr(0, dot))];
            parent = dot == std::string_view::npos ? std::string_view() : parent.substr(dot + 1);
        }
        json& slot = (*o)[std::string(f.key())];
        switch (f.kind()) {
            case FieldKind::Text:
                slot = f.text(h);
                break;
            case FieldKind::Number:
                slot = f.number(h);
                break;
            case FieldKind::Integer:
                slot = f.integer(h);
                break;
            case FieldKind::Boolean:
                slot = f.boolean(h);
                break;
            case FieldKind::Choice:
                slot = f.choices[static_cast<std::size_t>(f.get_choice(h))];
                break;
            case FieldKind::Seed:
                slot = f.seed(h);
                break;
            case FieldKind::Size3:
                slot = f.size3(h);
                break;
        }
    }
}

template <class Host>
void check_ranges(const Host& host, std::span<const FieldOf<Host>> fields,
                  const std::string& prefix, const std::string& file,
                  std::vector<Problem>& problems) {
    Host& h = const_cast<Host&>(host);  // read only
    for (const auto& f : fields) {
        const std::string field = join(prefix, f.path);
        switch (f.kind()) {
            case FieldKind::Number:
                if (!f.range.contains(f.number(h)))
                    problems.push_back({file, field, range_message(f)});
                break;
            case FieldKind::Integer:
                if (!f.range.contains(f.integer(h)))
                    problems.push_back({file, field, range_message(f)});
                break;
            case FieldKind::Size3:
                for (int i = 0; i < 3; ++i)
                    if (!f.range.contains(f.size3(h)[i]))
                        problems.push_back(
                            {file, field + "[" + std::to_string(i) + "]",
                             range_message(f) + ", got " + std::to_string(f.size3(h)[i])});
                break;
            default:
                break;
        }
    }
}

template void read_fields(JsonReader&, const json&, const std::string&,
                          std::span<const ExperimentField>, Experiment&, const ExtraKeys&);
template void read_fields(JsonReader&, const json&, const std::string&,
                          std::span<const MaterialField>, engine::Material&, const ExtraKeys&);
template void write_fields(const Experiment&, std::span<const ExperimentField>, json&);
template void write_fields(const engine::Material&, std::span<const MaterialField>, json&);
template void check_ranges(const Experiment&, std::span<const ExperimentField>, const std::string&,
                           const std::string&, std::vector<Problem>&);
template void check_ranges(const engine::Material&, std::span<const MaterialField>,
                           const std::string&, const std::string&, std::vector<Problem>&);

}  // namespace bhm::evo
