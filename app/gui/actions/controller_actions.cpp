// Export and reuse of controllers in the studio (controller_actions.hpp).
#include "app/gui/actions/controller_actions.hpp"

#include <filesystem>
#include <stdexcept>

#include "app/gui/actions/studio_actions.hpp"
#include "evo/evaluate/robustness.hpp"
#include "evo/experiment/experiment_io.hpp"
#include "evo/genome/controller.hpp"

namespace bhm::app::gui {

std::optional<nlohmann::json> shown_controller(Studio& s) {
    const auto& shown = s.bodies.shown;
    if (!shown) return std::nullopt;
    if (!s.bodies.driven_controller.empty() && shown->label == s.bodies.driven_label)
        return nlohmann::json::parse(s.bodies.driven_controller);
    if (shown->id < 0 || !s.run.snapshot) return std::nullopt;
    s.run.champion_history.refresh(s.run.snapshot->run_dir);
    for (const ChampionEntry& e : s.run.champion_history.entries())
        if (e.id == shown->id) return load_champion_controller(e.path);
    return std::nullopt;
}

bool export_shown_controller(Studio& s, const std::string& path) {
    try {
        const auto controller = shown_controller(s);
        if (!controller) {
            set_status(s,
                       s.bodies.shown ? "export controller: the body shown has no controller CPPN "
                                        "(a champion of a run of evolution.controller coevolve or "
                                        "fixed_body has one)"
                                      : "export controller: no body shown",
                       true);
            return false;
        }
        const auto parent = std::filesystem::path(path).parent_path();
        if (!parent.empty()) std::filesystem::create_directories(parent);
        evo::write_file_atomically(path, controller->dump(2) + "\n");
        set_status(s, "controller written: " + path);
        return true;
    } catch (const std::exception& e) {
        set_status(s, std::string("export controller: ") + e.what(), true);
        return false;
    }
}

bool drive_shown_body(Studio& s, const std::string& item) {
    const auto& shown = s.bodies.shown;
    if (!shown || !shown->framed_body) {
        set_status(s, "controller: no body shown to drive", true);
        return false;
    }
    try {
        const evo::RobustnessController controller =
            evo::resolve_robustness_controller(item, shown->experiment.evolution.cppn.weight_range);
        auto body = std::make_shared<evo::Body>(*shown->framed_body);
        evo::paint_controller_entry(controller.entry, shown->experiment.evolution.cppn.weight_range,
                                    shown->experiment.materials, *body);
        SimulationRequest request;
        request.label = shown->label + " driven by " + item;
        request.experiment = shown->experiment;
        request.framed_body = std::move(body);
        s.bodies.driven_label = request.label;
        s.bodies.driven_controller = controller.entry.genome_json;  // "" for a built-in
        s.bodies.follow_champion = false;
        s.bodies.simulator.request(std::move(request));
        set_status(s, "simulating " + s.bodies.driven_label);
        return true;
    } catch (const std::exception& e) {
        set_status(s, std::string("controller: ") + e.what(), true);
        return false;
    }
}

}  // namespace bhm::app::gui
