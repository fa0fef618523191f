#pragma once
// Strict typed access to a JSON object for the files evolution writes itself (checkpoints, run
// results, the evaluation wire): the first missing or mistyped field throws a FieldError that
// names its JSON path, e.g. "population[3].report.measures.tip: expected a number". (Files a
// person writes go through JsonReader, which collects every problem instead.)
#include <cstdint>
#include <stdexcept>
#include <string>

#include <nlohmann/json.hpp>

namespace bhm::evo {

struct FieldError : std::runtime_error {
    using std::runtime_error::runtime_error;
};

//! Typed access that names the JSON path of whatever is missing or wrong.
class Fields {
  public:
    Fields(const nlohmann::json& j, std::string path) : j_(j), path_(std::move(path)) {
        if (!j_.is_object()) fail("", "expected an object");
    }
    [[noreturn]] void fail(const std::string& key, const std::string& message) const {
        throw FieldError(join(key) + ": " + message);
    }
    std::string join(const std::string& key) const {
        if (key.empty()) return path_.empty() ? "(root)" : path_;
        return path_.empty() ? key : path_ + "." + key;
    }
    bool has(const std::string& key) const { return j_.contains(key); }
    const nlohmann::json& at(const std::string& key) const {
        const auto it = j_.find(key);
        if (it == j_.end()) fail(key, "missing");
        return *it;
    }
    double number(const std::string& key) const {
        const auto& v = at(key);
        if (!v.is_number()) fail(key, "expected a number");
        return v.get<double>();
    }
    std::int64_t integer(const std::string& key) const {
        const auto& v = at(key);
        if (!v.is_number_integer()) fail(key, "expected an integer");
        return v.get<std::int64_t>();
    }
    //! A non-negative integer up to 2^64 - 1 (a seed written as a number).
    std::uint64_t unsigned64(const std::string& key) const {
        const auto& v = at(key);
        if (!v.is_number_integer() || (!v.is_number_unsigned() && v.get<std::int64_t>() < 0))
            fail(key, "expected a non-negative integer");
        return v.get<std::uint64_t>();
    }
    bool boolean(const std::string& key) const {
        const auto& v = at(key);
        if (!v.is_boolean()) fail(key, "expected true or false");
        return v.get<bool>();
    }
    std::string string(const std::string& key) const {
        const auto& v = at(key);
        if (!v.is_string()) fail(key, "expected a string");
        return v.get<std::string>();
    }
    std::uint64_t hex64(const std::string& key) const {
        const std::string s = string(key);
        return parse_hex(s, join(key));
    }
    const nlohmann::json& array(const std::string& key) const {
        const auto& v = at(key);
        if (!v.is_array()) fail(key, "expected an array");
        return v;
    }
    static std::uint64_t parse_hex(const std::string& s, const std::string& where) {
        if (s.empty() || s.size() > 16 ||
            s.find_first_not_of("0123456789abcdef") != std::string::npos)
            throw FieldError(where + ": expected up to 16 lowercase hex digits");
        return std::stoull(s, nullptr, 16);
    }

  private:
    const nlohmann::json& j_;
    std::string path_;
};

//! "path[i]": the JSON path of an array's element.
inline std::string item(const std::string& path, std::size_t i) {
    return path + "[" + std::to_string(i) + "]";
}

}  // namespace bhm::evo
