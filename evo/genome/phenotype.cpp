#include "evo/genome/phenotype.hpp"

#include <stdexcept>

#include "evo/experiment/body_spec_of.hpp"
#include "evo/genome/body_ops.hpp"
#include "evo/genome/controller.hpp"

namespace bhm::evo {

DesignSpace design_space(const Experiment& experiment) {
    const auto& t = experiment.boundary.enclosure_thickness;
    DesignSpace space;
    for (int axis = 0; axis < 3; ++axis) {
        space.origin[static_cast<std::size_t>(axis)] = t[static_cast<std::size_t>(2 * axis)];
        space.size[static_cast<std::size_t>(axis)] =
            experiment.workspace_size[static_cast<std::size_t>(axis)] -
            t[static_cast<std::size_t>(2 * axis)] - t[static_cast<std::size_t>(2 * axis + 1)];
    }
    return space;
}

namespace {

CppnMaterials checked_materials(const Experiment& experiment) {
    const auto m = cppn_materials(experiment);
    if (!m.palette.empty()) return m;  // per-material outputs can paint any material
    // fixed_body: no body CPPN paints anything, so the palette needs neither kind.
    if (experiment.evolution.controller.mode == ControllerMode::FixedBody) return m;
    if (m.passive == 0)
        throw std::invalid_argument(
            "experiment '" + experiment.name +
            "': materials: the CPPN needs a passive material (cte_per_c == 0)");
    if (m.active == 0)
        throw std::invalid_argument(
            "experiment '" + experiment.name +
            "': materials: the CPPN needs an active material (cte_per_c > 0, or a muscle "
            "with muscle.contraction_strain > 0)");
    return m;
}

std::array<int, 3> checked_size(const DesignSpace& space, const std::string& name) {
    for (int s : space.size)
        if (s <= 0)
            throw std::invalid_argument("experiment '" + name +
                                        "': boundary.enclosure: the frame leaves no design space");
    return space.size;
}

}  // namespace

Developer::Developer(const Experiment& experiment)
    : experiment_(experiment),
      space_(design_space(experiment)),
      decoder_(checked_size(space_, experiment.name), checked_materials(experiment),
               cppn_fibres(experiment)),
      output_count_(decoder_.output_count()) {
    const ControllerSettings& c = experiment.evolution.controller;
    if (c.mode == ControllerMode::FixedBody) {
        if (!c.body)
            throw std::invalid_argument("experiment '" + experiment.name +
                                        "': evolution.controller.body: is required in mode "
                                        "fixed_body");
        output_count_ = kControllerOutputCount;
        Body body = *c.body;  // the body's own controller, if any, is what gets evolved
        body.phase.clear();
        body.amplitude.clear();
        fixed_framed_ = apply_frame_and_overrides(experiment, body);
    }
    if (experiment.evolution.algorithm == Algorithm::HyperNeat) {
        // The substrate lies over the lattice the direct CPPN would paint: the design space for a
        // body, the framed workspace for a controller; its output sheets are that CPPN's outputs.
        const auto lattice = c.mode == ControllerMode::FixedBody ? fixed_framed_.size : space_.size;
        substrate_ = std::make_shared<const HyperNeatSubstrate>(lattice, output_count_,
                                                                experiment.evolution.hyperneat);
        output_count_ = substrate_->cppn_output_count();
        input_count_ = kHyperNeatInputCount;
    }
    // fixed_controllers: a controller file's CPPN is read here, before any simulation, so that
    // a bad one is one line naming its entry (the experiment reader checks only its envelope).
    for (std::size_t i = 0; i < c.controllers.size(); ++i) {
        if (c.controllers[i].genome_json.empty()) continue;
        try {
            controller_program_from_json(nlohmann::json::parse(c.controllers[i].genome_json),
                                         experiment.evolution.cppn.weight_range);
        } catch (const std::exception& e) {
            throw std::invalid_argument("experiment '" + experiment.name +
                                        "': evolution.controller.controllers[" + std::to_string(i) +
                                        "] (" + c.controllers[i].name + "): " + e.what());
        }
    }
}

Body Developer::decode_raw(const Genome& genome) const {
    return substrate_ ? decoder_.paint(substrate_->activate(genome)) : decoder_.decode(genome);
}

Phenotype Developer::develop(const Genome& genome) const {
    Phenotype p;
    if (controller_mode() == ControllerMode::FixedBody) {
        p.body = fixed_framed_;
        if (substrate_) {
            const auto out = substrate_->activate(genome);
            paint_controller_outputs(out[0], out[1], experiment_.materials, p.body);
        } else {
            paint_controller(genome, experiment_.materials, p.body);
        }
    } else {
        const Body designed = largest_face_connected_component(decode_raw(genome));
        p.body = apply_frame_and_overrides(experiment_, designed);
    }
    count(p);
    return p;
}

Phenotype Developer::develop(const Genome& genome, const Genome& controller) const {
    if (controller_mode() != ControllerMode::Coevolve) return develop(genome);
    Phenotype p = develop(genome);
    paint_controller(controller, experiment_.materials, p.body);
    count(p);
    return p;
}

void Developer::count(Phenotype& p) const {
    p.designed_voxels = 0;
    p.hash = hash_body(p.body);
    p.voxels = count_filled(p.body);
    p.active_voxels = count_active(p.body, experiment_.materials);
    for (int z = 0; z < p.body.size[2]; ++z)
        for (int y = 0; y < p.body.size[1]; ++y)
            for (int x = 0; x < p.body.size[0]; ++x)
                if (space_.contains(x, y, z) &&
                    p.body.cells[static_cast<std::size_t>(p.body.index(x, y, z))])
                    ++p.designed_voxels;
}

}  // namespace bhm::evo
