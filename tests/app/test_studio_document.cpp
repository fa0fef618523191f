// The studio's document: validated edits, undo / redo, and the painter's edits as pure functions.
#include <doctest/doctest.h>

#include "app/gui/document/constraint_edits.hpp"
#include "app/gui/document/experiment_document.hpp"
#include "app/gui/document/studio_defaults.hpp"
#include "evo/experiment/experiment_io.hpp"
#include "test_studio_fixtures.hpp"

using namespace bhm;
using namespace bhm::app::gui;

TEST_CASE("studio document: the default experiment is valid and holds the paper's materials") {
    const auto e = default_experiment();
    CHECK(evo::validate_experiment(e, "default").empty());
    REQUIRE(e.materials.size() == 2);
    CHECK(e.materials[0].physics.youngs_modulus_pa == 5e6);
    CHECK(e.materials[0].physics.density_kg_m3 == 1000.0);
    CHECK(e.materials[0].physics.poisson_ratio == 0.35);
    CHECK(e.materials[1].physics.cte_per_c == 0.01);
    CHECK(e.materials[0].physics.static_friction == 1.0);
    CHECK(e.materials[0].physics.dynamic_friction == 0.5);
    CHECK(e.actuation.frequency_hz == 2.0);
    CHECK(e.simulation.settle_s == 1.0);
    CHECK(e.simulation.evaluate_s == 10.0);
}

TEST_CASE("studio document: edits record undo, undo and redo walk the history") {
    ExperimentDocument doc;
    doc.reset(testing::tiny_experiment(), "tiny.json");
    CHECK_FALSE(doc.dirty());
    CHECK_FALSE(doc.can_undo());
    const auto original = doc.experiment();

    auto longer = original;
    longer.simulation.evaluate_s = 2.5;
    CHECK(doc.edit(longer, "evaluation time").empty());
    auto fixed = longer;
    fixed.boundary.faces[1] = evo::BoundaryKind::Fixed;
    CHECK(doc.edit(fixed, "face x+ fixed").empty());
    CHECK(doc.dirty());
    CHECK(doc.experiment().boundary.faces[1] == evo::BoundaryKind::Fixed);
    CHECK(doc.undo_label() == "face x+ fixed");

    CHECK(doc.undo());
    CHECK(doc.experiment() == longer);
    CHECK(doc.redo_label() == "face x+ fixed");
    CHECK(doc.undo());
    CHECK(doc.experiment() == original);
    CHECK_FALSE(doc.dirty());  // back at the saved state
    CHECK_FALSE(doc.undo());
    CHECK(doc.redo());
    CHECK(doc.redo());
    CHECK(doc.experiment() == fixed);
    CHECK_FALSE(doc.redo());

    // An edit after undo drops the redo branch.
    CHECK(doc.undo());
    auto other = longer;
    other.simulation.settle_s = 0.2;
    CHECK(doc.edit(other, "settle").empty());
    CHECK_FALSE(doc.can_redo());
}

TEST_CASE("studio document: an invalid edit is refused with the validator's message") {
    ExperimentDocument doc;
    const auto before = doc.experiment();
    const auto revision = doc.revision();
    auto bad = before;
    bad.materials[0].physics.poisson_ratio = 0.7;
    const auto problems = doc.edit(bad, "Poisson ratio");
    REQUIRE(problems.size() == 1);
    CHECK(problems[0].field == "materials[0].poisson_ratio");
    CHECK(problems[0].message.find("0.49") != std::string::npos);
    CHECK(doc.experiment() == before);
    CHECK(doc.revision() == revision);
    CHECK_FALSE(doc.can_undo());
    // An unchanged experiment records nothing.
    CHECK(doc.edit(before, "nothing").empty());
    CHECK_FALSE(doc.can_undo());
}

TEST_CASE("studio document: the history keeps the newest edits") {
    ExperimentDocument doc;
    auto e = doc.experiment();
    for (std::size_t i = 0; i < ExperimentDocument::kMaxHistory + 20; ++i) {
        e.evolution.seed = i + 100;
        REQUIRE(doc.edit(e, "seed").empty());
    }
    int undos = 0;
    while (doc.undo())
        ++undos;
    CHECK(undos == static_cast<int>(ExperimentDocument::kMaxHistory));
    CHECK(doc.experiment().evolution.seed == 100 + 20 - 1);
    CHECK(doc.dirty());  // the saved state fell off the history
}

TEST_CASE(
    "studio constraint edits: faces cycle, frames get a passive material, overrides replace") {
    const auto e = testing::tiny_experiment({5, 4, 3});
    CHECK(next_face_kind(evo::BoundaryKind::Free) == evo::BoundaryKind::Fixed);
    CHECK(next_face_kind(evo::BoundaryKind::Fixed) == evo::BoundaryKind::Free);
    const auto cycled = with_face_cycled(e, evo::Face::ZMax);
    CHECK(cycled.boundary.faces[static_cast<int>(evo::Face::ZMax)] == evo::BoundaryKind::Fixed);
    CHECK(with_face_cycled(cycled, evo::Face::ZMax) == e);

    const auto framed = with_enclosure_thickness(e, evo::Face::YMin, 1);
    CHECK(framed.boundary.enclosure_thickness[static_cast<int>(evo::Face::YMin)] == 1);
    CHECK(framed.boundary.enclosure_material == 1);  // the passive one, required by the format
    CHECK(evo::validate_experiment(framed, "t").empty());

    auto painted = with_override(e, {1, 2, 0}, PaintKind::Empty);
    REQUIRE(painted.boundary.voxel_overrides.size() == 1);
    CHECK(painted.boundary.voxel_overrides[0].kind == evo::OverrideKind::Empty);
    painted = with_override(painted, {1, 2, 0}, PaintKind::Material, 2);
    REQUIRE(painted.boundary.voxel_overrides.size() == 1);  // replaced, not added
    CHECK(painted.boundary.voxel_overrides[0].kind == evo::OverrideKind::Material);
    CHECK(painted.boundary.voxel_overrides[0].material == 2);
    painted = with_override(painted, {0, 0, 0}, PaintKind::Fixed);
    CHECK(find_override(painted, {0, 0, 0}) == 1);
    CHECK(find_override(painted, {4, 3, 2}) == -1);
    CHECK(evo::validate_experiment(painted, "t").empty());
    painted = with_override(painted, {1, 2, 0}, PaintKind::Clear);
    CHECK(painted.boundary.voxel_overrides.size() == 1);
    CHECK(paint_edit_label({1, 2, 0}, PaintKind::Empty, 0) == "voxel (1, 2, 0) forbidden");
    CHECK(face_edit_label(evo::Face::XMax, evo::BoundaryKind::Fixed) == "face x+ fixed");
}
