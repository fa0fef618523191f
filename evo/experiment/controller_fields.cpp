// evolution.controller's body and controllers (controller_fields.hpp).
#include "evo/experiment/controller_fields.hpp"

#include <filesystem>

#include "engine/io/text_file.hpp"

namespace bhm::evo {

namespace {

constexpr const char* kPath = "evolution.controller";
const char* const kBuiltins[] = {"uniform", "random", "wave"};

bool is_builtin(const std::string& name) {
    for (const char* b : kBuiltins)
        if (name == b) return true;
    return false;
}

// A controller file's object, checked only for its envelope here (the genome's reader,
// evo/genome/controller.hpp, is a later folder and checks the rest when a run starts).
void read_inline(JsonReader& r, const nlohmann::json& controller, const std::string& field,
                 ControllerEntry& entry) {
    if (!controller.is_object() || !controller.contains("genome") ||
        !controller["genome"].is_object())
        r.problem(field,
                  "expected a controller file's object with \"format\": "
                  "\"bhm-controller\" and a \"genome\"");
    else
        entry.genome_json = controller.dump();
}

ControllerEntry read_entry(JsonReader& r, const nlohmann::json& item, const std::string& field,
                           const std::string& experiment_path) {
    ControllerEntry entry;
    if (item.is_string()) {
        entry.name = item.get<std::string>();
        if (is_builtin(entry.name)) return entry;
        // A controller file, relative to the experiment file.
        std::filesystem::path p(entry.name);
        if (p.is_relative() && !experiment_path.empty())
            p = std::filesystem::path(experiment_path).parent_path() / p;
        try {
            read_inline(r,
                        nlohmann::json::parse(engine::read_text(p.string(), engine::kTextFileCap)),
                        field, entry);
        } catch (const std::exception& ex) {
            r.problem(field, "\"" + entry.name +
                                 "\" is neither a built-in controller (uniform, random, wave) "
                                 "nor a readable controller file: " +
                                 without_json_tags(ex.what()));
        }
        return entry;
    }
    if (!item.is_object()) {
        r.problem(field,
                  "expected \"uniform\", \"random\", \"wave\", a controller file's path or "
                  "an object");
        return entry;
    }
    if (item.contains("builtin")) {
        r.check_keys(item, field, {"builtin", "seed"});
        entry.name = kBuiltins[r.choice(item, "builtin", field, {"uniform", "random", "wave"}, 0)];
        entry.seed =
            static_cast<std::uint64_t>(r.integer(item, "seed", field, 1, 0, 9007199254740991LL));
        return entry;
    }
    r.check_keys(item, field, {"name", "controller"});
    entry.name = r.string(item, "name", field, "controller");
    if (!item.contains("controller"))
        r.problem(JsonReader::join(field, "controller"), "is required");
    else
        read_inline(r, item["controller"], JsonReader::join(field, "controller"), entry);
    return entry;
}

}  // namespace

void parse_controller_settings(JsonReader& r, const nlohmann::json& evolution,
                               const std::string& experiment_path, ControllerSettings& out) {
    const auto c = evolution.find("controller");
    if (c == evolution.end() || !c->is_object()) return;  // a wrong type: read_fields reported it
    if (const auto b = c->find("body"); b != c->end()) {
        try {
            out.body = parse_body(*b, experiment_path + ":" + kPath + ".body");
        } catch (const ValidationError& e) {
            for (const Problem& p : e.problems)
                r.problem(std::string(kPath) + ".body." + p.field, p.message);
        }
    }
    if (const auto list = c->find("controllers"); list != c->end()) {
        const std::string field = std::string(kPath) + ".controllers";
        if (!list->is_array()) {
            r.problem(field, "expected an array of controllers");
            return;
        }
        for (std::size_t i = 0; i < list->size(); ++i)
            out.controllers.push_back(
                read_entry(r, (*list)[i], field + "[" + std::to_string(i) + "]", experiment_path));
    }
}

std::vector<Problem> controller_problems(const Experiment& e, const std::string& file) {
    std::vector<Problem> problems;
    const ControllerSettings& c = e.evolution.controller;
    const std::string path = kPath;
    if (c.mode == ControllerMode::FixedBody) {
        if (!c.body)
            problems.push_back({file, path + ".body",
                                "is required in mode fixed_body (or bhm evolve --body B.json)"});
        else
            for (Problem p : validate_body_against(*c.body, e, file)) {
                p.field = path + ".body." + p.field;
                problems.push_back(p);
            }
    } else if (c.body) {
        problems.push_back({file, path + ".body", "is used only in mode fixed_body"});
    }
    if (c.mode == ControllerMode::FixedControllers && c.controllers.empty())
        problems.push_back({file, path + ".controllers",
                            "needs at least one controller in mode fixed_controllers"});
    if (c.mode != ControllerMode::FixedControllers && !c.controllers.empty())
        problems.push_back({file, path + ".controllers", "is used only in mode fixed_controllers"});
    return problems;
}

void write_controller_settings(const ControllerSettings& settings, nlohmann::json& evolution) {
    if (settings == ControllerSettings{}) {
        evolution.erase("controller");
        return;
    }
    nlohmann::json& c = evolution["controller"];
    if (settings.body) c["body"] = body_to_json(*settings.body);
    if (!settings.controllers.empty()) {
        nlohmann::json list = nlohmann::json::array();
        for (const ControllerEntry& entry : settings.controllers) {
            if (!entry.genome_json.empty())
                list.push_back({{"name", entry.name},
                                {"controller", nlohmann::json::parse(entry.genome_json)}});
            else if (entry.name == "random")
                list.push_back({{"builtin", "random"}, {"seed", entry.seed}});
            else
                list.push_back(entry.name);
        }
        c["controllers"] = list;
    }
}

}  // namespace bhm::evo
