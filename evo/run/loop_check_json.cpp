#include "evo/run/loop_check_json.hpp"

#include <algorithm>
#include <cinttypes>
#include <cstdio>

#include "evo/experiment/experiment_io.hpp"
#include "evo/experiment/json_fields.hpp"
#include "evo/genome/body_ops.hpp"

namespace bhm::evo {

namespace {

template <std::size_t N>
int choice_index(const std::array<const char*, N>& names, const Fields& f, const std::string& key) {
    const std::string value = f.string(key);
    for (std::size_t i = 0; i < N; ++i)
        if (value == names[i]) return static_cast<int>(i);
    std::string accepted;
    for (const char* n : names)
        accepted += (accepted.empty() ? "" : ", ") + std::string(n);
    f.fail(key, "'" + value + "' is not one of " + accepted);
    return 0;
}

std::string hex(std::uint64_t v) {
    char buffer[24];
    std::snprintf(buffer, sizeof buffer, "%016" PRIx64, v);
    return buffer;
}

}  // namespace

nlohmann::json loop_check_to_json(const LoopCheck& c) {
    return {{"generation", c.generation},
            {"id", c.id},
            {"phenotype_hash", hex(c.hash)},
            {"outcome", kLoopCheckOutcomeNames[static_cast<std::size_t>(c.outcome)]},
            {"worst", c.worst},
            {"fem_score", c.fem_score},
            {"engine_score", c.engine_score},
            {"verdict", c.verdict},
            {"laws", c.laws}};
}

LoopCheck loop_check_from_json(const nlohmann::json& j, const std::string& path) {
    const Fields f(j, path);
    LoopCheck c;
    c.generation = static_cast<int>(f.integer("generation"));
    c.id = f.integer("id");
    c.hash = f.hex64("phenotype_hash");
    c.outcome = static_cast<LoopCheckOutcome>(choice_index(kLoopCheckOutcomeNames, f, "outcome"));
    c.worst = f.number("worst");
    c.fem_score = f.number("fem_score");
    c.engine_score = f.number("engine_score");
    c.verdict = f.string("verdict");
    if (f.has("laws")) {  // absent before the loop solved its laws one at a time
        const auto& laws = f.array("laws");
        for (std::size_t i = 0; i < laws.size(); ++i) {
            if (!laws[i].is_string())
                f.fail("laws", "item " + std::to_string(i) + " is not a string");
            c.laws.push_back(laws[i].get<std::string>());
        }
    }
    return c;
}

nlohmann::json pending_checks_to_json(const PendingChecks& pending) {
    nlohmann::json picks = nlohmann::json::array();
    for (const auto& p : pending.picks)
        picks.push_back(
            {{"id", p.id}, {"phenotype_hash", hex(p.hash)}, {"body", body_to_json(p.body)}});
    return {{"generation", pending.generation}, {"picks", picks}};
}

PendingChecks pending_checks_from_json(const nlohmann::json& j, const std::string& path) {
    const Fields f(j, path);
    PendingChecks pending;
    pending.generation = static_cast<int>(f.integer("generation"));
    const auto& picks = f.array("picks");
    for (std::size_t i = 0; i < picks.size(); ++i) {
        const Fields p(picks[i], item(f.join("picks"), i));
        LoopCheckRequest request;
        request.id = p.integer("id");
        request.hash = p.hex64("phenotype_hash");
        try {
            request.body = parse_body(p.at("body"), p.join("body"));
        } catch (const std::exception& e) {
            throw FieldError(e.what());
        }
        if (hash_body(request.body) != request.hash)
            p.fail("body", "does not match its phenotype_hash");
        pending.picks.push_back(std::move(request));
    }
    return pending;
}

nlohmann::json loop_verify_settings_to_json(const LoopVerifySettings& s) {
    return {{"every_generations", s.every_generations},
            {"top_k", s.top_k},
            {"policy", kVerifyPolicyNames[static_cast<std::size_t>(s.policy)]},
            {"tolerance", s.tolerance}};
}

LoopVerifySettings loop_verify_settings_from_json(const nlohmann::json& j,
                                                  const std::string& path) {
    const Fields f(j, path);
    LoopVerifySettings s;
    s.every_generations = static_cast<int>(f.integer("every_generations"));
    s.top_k = static_cast<int>(f.integer("top_k"));
    s.policy = static_cast<VerifyPolicy>(choice_index(kVerifyPolicyNames, f, "policy"));
    s.tolerance = f.number("tolerance");
    if (s.every_generations < 0) f.fail("every_generations", "must be >= 0");
    if (s.top_k < 1) f.fail("top_k", "must be >= 1");
    if (!(s.tolerance > 0.0)) f.fail("tolerance", "must be above 0");
    return s;
}

nlohmann::json loop_check_row_to_json(const LoopCheckRow& row) {
    nlohmann::json j = {{"verified", row.verified}};
    j["champion_agrees"] = row.champion_agrees ? nlohmann::json(*row.champion_agrees) : nullptr;
    j["worst_difference"] =
        row.worst_difference ? nlohmann::json(*row.worst_difference) : nullptr;
    return j;
}

LoopCheckRow loop_check_row_from_json(const nlohmann::json& j, const std::string& path) {
    const Fields f(j, path);
    LoopCheckRow row;
    row.verified = static_cast<int>(f.integer("verified"));
    if (!f.at("champion_agrees").is_null()) row.champion_agrees = f.boolean("champion_agrees");
    if (!f.at("worst_difference").is_null()) row.worst_difference = f.number("worst_difference");
    return row;
}

}  // namespace bhm::evo
