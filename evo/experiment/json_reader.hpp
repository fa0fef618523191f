#pragma once
// A JSON walker that collects every problem instead of stopping at the first: each accessor
// reads one field with its default, checks type and range, and records "file:field: message".
#include <array>
#include <cstdint>
#include <functional>
#include <optional>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "evo/experiment/experiment_io.hpp"

namespace bhm::evo {

//! A message without nlohmann's "[json.exception.type_error.302] " tags, wherever they sit (a
//! wrapped message carries them inside): no library's internal codes reach a user.
std::string without_json_tags(std::string text);

//! Levenshtein distance, for "did you mean" suggestions.
int edit_distance(const std::string& a, const std::string& b);
//! The closest candidate within a small edit distance, or "".
std::string closest_match(const std::string& word, const std::vector<std::string>& candidates);

class JsonReader {
  public:
    JsonReader(std::string file_label, std::vector<Problem>& problems)
        : file_(std::move(file_label)), problems_(problems) {}

    void problem(const std::string& field, const std::string& message) {
        problems_.push_back({file_, field, message});
    }

    //! Reports keys of obj that are not in known (with a suggestion). obj must be an object.
    void check_keys(const nlohmann::json& obj, const std::string& path,
                    const std::vector<std::string>& known);

    //! Returns obj[key] when it is an object; reports a type error; nullptr when absent/invalid.
    const nlohmann::json* object(const nlohmann::json& obj, const std::string& key,
                                 const std::string& path);

    double number(const nlohmann::json& obj, const std::string& key, const std::string& path,
                  double fallback, std::optional<double> min = {}, std::optional<double> max = {},
                  bool min_exclusive = false, bool max_exclusive = false);
    long long integer(const nlohmann::json& obj, const std::string& key, const std::string& path,
                      long long fallback, long long min, long long max);
    bool boolean(const nlohmann::json& obj, const std::string& key, const std::string& path,
                 bool fallback);
    std::string string(const nlohmann::json& obj, const std::string& key, const std::string& path,
                       const std::string& fallback);
    //! An array of 3 integers [x, y, z] into out; out is left as it was when absent or invalid.
    void array3(const nlohmann::json& obj, const std::string& key, const std::string& path,
                std::array<int, 3>& out);
    //! A string that must be one of choices; returns its index or fallback_index.
    int choice(const nlohmann::json& obj, const std::string& key, const std::string& path,
               const std::vector<std::string>& choices, int fallback_index);

    static std::string join(const std::string& path, const std::string& key) {
        return path.empty() ? key : path + "." + key;
    }
    static std::string type_name(const nlohmann::json& v);

  private:
    std::string file_;
    std::vector<Problem>& problems_;
};

}  // namespace bhm::evo
