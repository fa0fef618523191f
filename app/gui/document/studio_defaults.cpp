#include "app/gui/document/studio_defaults.hpp"

namespace bhm::app::gui {

evo::Experiment default_experiment() {
    evo::Experiment e;  // evo's defaults are the paper's values where the paper gives them
    e.name = "untitled";
    e.description = "New experiment: paper Table 1 materials, 2 Hz, 1 s settle + 10 s actuated.";
    evo::MaterialEntry passive;
    passive.name = "passive tissue";
    passive.physics.cte_per_c = 0.0;
    passive.color = {0.70f, 0.80f, 0.92f};
    passive.has_color = true;
    evo::MaterialEntry active = passive;
    active.name = "muscle (active)";
    active.physics.cte_per_c = 0.01;
    active.color = {0.86f, 0.22f, 0.20f};
    e.materials = {passive, active};
    e.boundary.faces[static_cast<int>(evo::Face::XMin)] = evo::BoundaryKind::Fixed;
    e.fitness.constraints.attached_to_fixed_face = true;
    return e;
}

}  // namespace bhm::app::gui
