#include "evo/experiment/json_reader.hpp"

#include <algorithm>
#include <cmath>
#include <sstream>

#include "engine/io/text_file.hpp"

namespace bhm::evo {

std::string without_json_tags(std::string text) {
    static constexpr std::string_view kTag = "[json.exception.";
    for (auto at = text.find(kTag); at != std::string::npos; at = text.find(kTag, at)) {
        auto end = text.find(']', at);
        if (end == std::string::npos) break;
        if (end + 1 < text.size() && text[end + 1] == ' ') ++end;
        text.erase(at, end + 1 - at);
    }
    return text;
}

int edit_distance(const std::string& a, const std::string& b) {
    std::vector<int> row(b.size() + 1);
    for (size_t j = 0; j <= b.size(); ++j)
        row[j] = static_cast<int>(j);
    for (size_t i = 1; i <= a.size(); ++i) {
        int diagonal = row[0];
        row[0] = static_cast<int>(i);
        for (size_t j = 1; j <= b.size(); ++j) {
            int above = row[j];
            int cost = a[i - 1] == b[j - 1] ? 0 : 1;
            row[j] = std::min({row[j] + 1, row[j - 1] + 1, diagonal + cost});
            diagonal = above;
        }
    }
    return row[b.size()];
}

std::string closest_match(const std::string& word, const std::vector<std::string>& candidates) {
    std::string best;
    int best_distance = std::max<int>(2, static_cast<int>(word.size()) / 3) + 1;
    for (const auto& c : candidates) {
        int d = edit_distance(word, c);
        if (d < best_distance) {
            best_distance = d;
            best = c;
        }
    }
    return best;
}

std::string JsonReader::type_name(const nlohmann::json& v) {
    if (v.is_null()) return "null";
    if (v.is_boolean()) return "a boolean";
    if (v.is_number()) return "a number";
    if (v.is_string()) return "a string";
    if (v.is_array()) return "an array";
    return "an object";
}

void JsonReader::check_keys(const nlohmann::json& obj, const std::string& path,
                            const std::vector<std::string>& known) {
    for (auto it = obj.begin(); it != obj.end(); ++it) {
        if (std::find(known.begin(), known.end(), it.key()) != known.end()) continue;
        std::string message = "unknown key";
        if (auto suggestion = closest_match(it.key(), known); !suggestion.empty())
            message += " (did you mean '" + suggestion + "'?)";
        problem(join(path, it.key()), message);
    }
}

const nlohmann::json* JsonReader::object(const nlohmann::json& obj, const std::string& key,
                                         const std::string& path) {
    auto it = obj.find(key);
    if (it == obj.end()) return nullptr;
    if (!it->is_object()) {
        problem(join(path, key), "expected an object, got " + type_name(*it));
        return nullptr;
    }
    return &*it;
}

double JsonReader::number(const nlohmann::json& obj, const std::string& key,
                          const std::string& path, double fallback, std::optional<double> min,
                          std::optional<double> max, bool min_exclusive, bool max_exclusive) {
    auto it = obj.find(key);
    if (it == obj.end()) return fallback;
    const std::string field = join(path, key);
    if (!it->is_number()) {
        problem(field, "expected a number, got " + type_name(*it));
        return fallback;
    }
    double v = it->get<double>();
    if (!std::isfinite(v)) {
        problem(field, "must be a finite number");
        return fallback;
    }
    bool below = min && (min_exclusive ? v <= *min : v < *min);
    bool above = max && (max_exclusive ? v >= *max : v > *max);
    if (below || above) {
        std::string range;
        if (min && max)
            range = std::string("in ") + (min_exclusive ? "(" : "[") + engine::format_number(*min) +
                    ", " + engine::format_number(*max) + (max_exclusive ? ")" : "]");
        else if (min)
            range = (min_exclusive ? "> " : ">= ") + engine::format_number(*min);
        else
            range = (max_exclusive ? "< " : "<= ") + engine::format_number(*max);
        problem(field, "must be " + range + ", got " + engine::format_number(v));
        return fallback;
    }
    return v;
}

long long JsonReader::integer(const nlohmann::json& obj, const std::string& key,
                              const std::string& path, long long fallback, long long min,
                              long long max) {
    auto it = obj.find(key);
    if (it == obj.end()) return fallback;
    const std::string field = join(path, key);
    if (!it->is_number()) {
        problem(field, "expected an integer, got " + type_name(*it));
        return fallback;
    }
    if (it->is_number_float()) {
        double d = it->get<double>();
        if (!std::isfinite(d) || d != std::floor(d) || std::fabs(d) > 9e15) {
            problem(field, "expected an integer, got " + engine::format_number(d));
            return fallback;
        }
    }
    long long v = 0;
    if (it->is_number_unsigned()) {
        auto u = it->get<std::uint64_t>();
        if (u > static_cast<std::uint64_t>(max)) {
            problem(field, "must be in [" + std::to_string(min) + ", " + std::to_string(max) +
                               "], got " + std::to_string(u));
            return fallback;
        }
        v = static_cast<long long>(u);
    } else if (it->is_number_integer()) {
        v = it->get<long long>();
    } else {
        v = static_cast<long long>(it->get<double>());
    }
    if (v < min || v > max) {
        problem(field, "must be in [" + std::to_string(min) + ", " + std::to_string(max) +
                           "], got " + std::to_string(v));
        return fallback;
    }
    return v;
}

bool JsonReader::boolean(const nlohmann::json& obj, const std::string& key, const std::string& path,
                         bool fallback) {
    auto it = obj.find(key);
    if (it == obj.end()) return fallback;
    if (!it->is_boolean()) {
        problem(join(path, key), "expected true or false, got " + type_name(*it));
        return fallback;
    }
    return it->get<bool>();
}

std::string JsonReader::string(const nlohmann::json& obj, const std::string& key,
                               const std::string& path, const std::string& fallback) {
    auto it = obj.find(key);
    if (it == obj.end()) return fallback;
    if (!it->is_string()) {
        problem(join(path, key), "expected a string, got " + type_name(*it));
        return fallback;
    }
    return it->get<std::string>();
}

int JsonReader::choice(const nlohmann::json& obj, const std::string& key, const std::string& path,
                       const std::vector<std::string>& choices, int fallback_index) {
    auto it = obj.find(key);
    if (it == obj.end()) return fallback_index;
    const std::string field = join(path, key);
    if (!it->is_string()) {
        problem(field, "expected a string, got " + type_name(*it));
        return fallback_index;
    }
    const auto value = it->get<std::string>();
    for (size_t i = 0; i < choices.size(); ++i)
        if (choices[i] == value) return static_cast<int>(i);
    std::string message = "'" + value + "' is not one of";
    for (const auto& c : choices)
        message += " " + c;
    if (auto suggestion = closest_match(value, choices); !suggestion.empty())
        message += " (did you mean '" + suggestion + "'?)";
    problem(field, message);
    return fallback_index;
}

void JsonReader::array3(const nlohmann::json& obj, const std::string& key, const std::string& path,
                        std::array<int, 3>& out) {
    auto it = obj.find(key);
    if (it == obj.end()) return;
    const std::string field = join(path, key);
    if (!it->is_array() || it->size() != 3) {
        problem(field, "expected an array of 3 integers [x, y, z]");
        return;
    }
    std::array<int, 3> v{};
    for (int i = 0; i < 3; ++i) {
        const nlohmann::json& e = (*it)[i];
        if (!e.is_number_integer() && !e.is_number_unsigned()) {
            problem(field + "[" + std::to_string(i) + "]",
                    "expected an integer, got " + type_name(e));
            return;
        }
        long long x = e.get<long long>();
        if (x < -1'000'000'000LL || x > 1'000'000'000LL) {
            problem(field + "[" + std::to_string(i) + "]", "is out of range");
            return;
        }
        v[i] = static_cast<int>(x);
    }
    out = v;
}

}  // namespace bhm::evo
