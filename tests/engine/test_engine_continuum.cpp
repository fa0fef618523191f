// The continuum suite of the shapes evolution makes (issue 40), first part: bodies held to the
// fixed face by 1, 2, 4 and 8 voxels (square, line and L-shaped patches, centred, at an edge and
// in a corner) and necks inside a body (1x1, 1x2, 2x1, 2x2), at nu 0, 0.35 and 0.49, at rest
// under gravity. Each body is a 6x4x4 block of E = 5 MPa from x = 1 to 6, and the x = 0 layer
// holds only the patch (or, for the necks, is held whole, with the x = 3 layer cut to the neck).
//
// References: bhm verify's continuum model (evo/verify/fem_model: C3D20R, the clamp at the held
// voxels' centres) with 2 and 4 elements per voxel edge, solved by CalculiX and stored below (the
// solves take about 40 s each at 4 per edge; "continuum: references" re-solves them). The
// 4-per-edge answer is the reference; its own uncertainty is taken as its change from 2 per edge.
// Checked on one case with a third mesh (p1c at nu 0.35, 6 per edge: 91,117 nodes, 378 s of ccx
// CPU, 8.9 GB): tip 2.7952 / 2.9507 / 2.9905 mm at 2 / 4 / 6 per edge, observed order 1.45, the
// Richardson limit 3.040 mm, 3.0 % beyond the 4-per-edge reference (com 2.9 %, order 1.49), well
// inside the 5.3 % change from 2 to 4. The re-entrant corners at the patch make the refined mesh
// always softer, by 1-22 % here (most at nu 0.49).
// Measures: the mean vertical displacement of the last layer's voxel centres (tip) and of all
// voxel centres (com), the engine's from evo's quasi-static answer (what bhm verify compares).
//
// The split: the engine's constants for confined link ends (engine/internal/link_confinement.hpp)
// were fitted on kFittingHalf only; kHeldOutHalf is judged here. docs/physics.md ("Narrow
// attachments and necks") has the table these cases print.
#include <doctest/doctest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <set>
#include <string>
#include <utility>
#include <vector>

#include "calculix.hpp"
#include "support/ccx_skip.hpp"
#include "evo/verify/ccx_deck.hpp"
#include "evo/verify/fem_model.hpp"
#include "evo/verify/quasi_static.hpp"

using namespace bhm;

namespace {

const std::vector<std::string> kFittingHalf = {"p1c",   "p2y",     "p4sq", "p4liney",
                                               "neck1", "neck2x2", "p8",   "full"};
const std::vector<std::string> kHeldOutHalf = {"p1e", "p1corner", "p2z", "p2ye",    "p4sqe",
                                               "p4L", "p4linez",  "p8z", "neck1x2", "neck2x1"};

// Every case's body: nx = 7, ny = nz = 4, voxel 0.01 m, E 5 MPa, density 1000, no floor.
engine::BodySpec continuum_body(const std::string& name, double nu) {
    engine::BodySpec s;
    s.nx = 7;
    s.ny = 4;
    s.nz = 4;
    s.voxel_size_m = 0.01;
    s.material.assign(s.cell_count(), 0);
    s.fixed.assign(s.cell_count(), 0);
    engine::Material m;
    m.youngs_modulus_pa = 5e6;
    m.poisson_ratio = nu;
    m.density_kg_m3 = 1000.0;
    s.materials = {m};
    s.environment.floor = false;
    for (int z = 0; z < s.nz; ++z)
        for (int y = 0; y < s.ny; ++y)
            for (int x = 1; x < s.nx; ++x)
                s.material[s.cell_index(x, y, z)] = 1;
    std::vector<std::pair<int, int>> patch;  // (y, z) of the held voxels in the x = 0 layer
    auto rect = [&](int y0, int y1, int z0, int z1) {
        for (int y = y0; y <= y1; ++y)
            for (int z = z0; z <= z1; ++z)
                patch.push_back({y, z});
    };
    auto neck = [&](int y0, int y1, int z0, int z1) {
        rect(0, 3, 0, 3);
        for (int y = 0; y < s.ny; ++y)
            for (int z = 0; z < s.nz; ++z)
                s.material[s.cell_index(3, y, z)] =
                    y >= y0 && y <= y1 && z >= z0 && z <= z1 ? 1 : 0;
    };
    if (name == "p1c")
        rect(1, 1, 1, 1);
    else if (name == "p1e")
        rect(1, 1, 0, 0);
    else if (name == "p1corner")
        rect(0, 0, 0, 0);
    else if (name == "p2y")
        rect(1, 2, 1, 1);
    else if (name == "p2z")
        rect(1, 1, 1, 2);
    else if (name == "p2ye")
        rect(1, 2, 0, 0);
    else if (name == "p4sq")
        rect(1, 2, 1, 2);
    else if (name == "p4sqe")
        rect(1, 2, 0, 1);
    else if (name == "p4liney")
        rect(0, 3, 1, 1);
    else if (name == "p4linez")
        rect(1, 1, 0, 3);
    else if (name == "p4L") {
        rect(1, 2, 1, 1);
        rect(1, 1, 2, 3);
    } else if (name == "p8")
        rect(0, 3, 1, 2);
    else if (name == "p8z")
        rect(1, 2, 0, 3);
    else if (name == "full")
        rect(0, 3, 0, 3);
    else if (name == "neck1")
        neck(1, 1, 1, 1);
    else if (name == "neck1x2")
        neck(1, 2, 1, 1);
    else if (name == "neck2x1")
        neck(1, 1, 1, 2);
    else if (name == "neck2x2")
        neck(1, 2, 1, 2);
    else
        FAIL("no continuum case " << name);
    for (auto [y, z] : patch) {
        s.material[s.cell_index(0, y, z)] = 1;
        s.fixed[s.cell_index(0, y, z)] = 1;
    }
    return s;
}

struct Measures {
    double tip = 0.0, com = 0.0;  // mean z displacement (m) of the last layer / of all voxels
};

// `z_of(i)`: the vertical displacement of the i-th voxel in lattice order.
template <class ZOf>
Measures measures(const engine::BodySpec& s, ZOf z_of) {
    Measures m;
    int i = 0, tips = 0;
    for (int c = 0; c < s.cell_count(); ++c) {
        if (s.material[c] == 0) continue;
        const double z = z_of(i++);
        m.com += z;
        if (c % s.nx == s.nx - 1) {
            m.tip += z;
            ++tips;
        }
    }
    m.tip /= tips;
    m.com /= i;
    return m;
}

Measures engine_measures(const engine::BodySpec& s) {
    const evo::QuasiStaticResult r = evo::engine_quasi_static(s, 0.0);
    REQUIRE_MESSAGE(r.settled, r.problem);
    return measures(s, [&](int i) { return r.displacement_m[i][2]; });
}

Measures fem_measures(const engine::BodySpec& s, int subdivision) {
    evo::FemMeshOptions o;
    o.element = evo::FemElement::C3D20R;
    o.subdivision = subdivision;
    const evo::FemModel model = evo::build_fem_model(s, o);
    const evo::CcxResult r =
        evo::run_ccx("continuum", evo::ccx_deck(model, s, {{"rest", 0.0}}, false), 2);
    const evo::NodalDisplacements& u = r.blocks.back();
    return measures(s, [&](int i) {
        double z = 0.0;
        for (auto [node, weight] : model.voxel_centre[i])
            z += weight * u.at(node)[2];
        return z;
    });
}

struct Reference {
    const char* name;
    double nu;
    double tip2, com2, tip4, com4;  // mm, at 2 and at 4 elements per voxel edge
};

// CalculiX 2.20 (Debian calculix-ccx), computed 2026-12-04 by "continuum: references".
const Reference kReferences[] = {
#include "continuum_references.inc"
};

const Reference& reference(const std::string& name, double nu) {
    for (const Reference& r : kReferences)
        if (name == r.name && std::abs(nu - r.nu) < 1e-9) return r;
    FAIL("no reference for " << name << " at nu " << nu);
    return kReferences[0];
}

// Prints "case nu ours / CalculiX (uncertainty) difference" and returns the worst difference.
double compare(const std::string& name, double nu) {
    const Reference& r = reference(name, nu);
    const Measures ours = engine_measures(continuum_body(name, nu));
    const double tip = ours.tip * 1e3 / r.tip4 - 1.0, com = ours.com * 1e3 / r.com4 - 1.0;
    std::printf(
        "%-9s nu %.2f  tip %8.4f / %8.4f mm (+-%4.1f %%) %+6.1f %%   com %8.4f / %8.4f mm "
        "(+-%4.1f %%) %+6.1f %%\n",
        name.c_str(), nu, ours.tip * 1e3, r.tip4, 100.0 * std::abs(r.tip4 / r.tip2 - 1.0),
        100.0 * tip, ours.com * 1e3, r.com4, 100.0 * std::abs(r.com4 / r.com2 - 1.0), 100.0 * com);
    return std::max(std::abs(tip), std::abs(com));
}

}  // namespace

TEST_CASE("continuum: the halves are disjoint and every case has its references") {
    std::set<std::string> fitting(kFittingHalf.begin(), kFittingHalf.end());
    for (const std::string& name : kHeldOutHalf) {
        CHECK_MESSAGE(fitting.count(name) == 0, name << " is in both halves");
        for (double nu : {0.0, 0.35, 0.49})
            CHECK(reference(name, nu).tip4 < 0.0);
    }
    for (const std::string& name : kFittingHalf)
        for (double nu : {0.0, 0.35, 0.49})
            CHECK(reference(name, nu).tip4 < 0.0);
}

// Before issue 40 (db6afc9) these were +12..+100 % (the engine sagged far more than the FEM).
// The target is 5 % at any nu; what holds today is the envelope below, which the test
// keeps (docs/physics.md lists the open cases: 2-voxel-tall stalks and necks at nu 0.49 are
// stiff, 1x2 necks at nu 0.35 soft).
TEST_CASE("continuum: held-out attachments and necks against CalculiX at nu 0, 0.35, 0.49") {
    for (const std::string& name : kHeldOutHalf)
        for (double nu : {0.0, 0.35, 0.49}) {
            CAPTURE(name);
            CAPTURE(nu);
            const double tolerance = nu < 0.4 ? 0.15 : 0.20;
            CHECK(compare(name, nu) <= tolerance);
        }
}

TEST_CASE("continuum: the stored references are CalculiX's (one case re-solved)") {
    if (bhm::test::skip_without_ccx()) return;
    const Reference& r = reference("p1e", 0.35);
    const Measures fem = fem_measures(continuum_body("p1e", 0.35), 2);
    CHECK(fem.tip * 1e3 == doctest::Approx(r.tip2).epsilon(0.002));
    CHECK(fem.com * 1e3 == doctest::Approx(r.com2).epsilon(0.002));
}

// The full suite: every case of both halves against the stored references (about a minute), and
// with BHM_CONTINUUM_RESOLVE=1 the references themselves re-solved at 2 and 4 elements per voxel
// edge (about an hour on one core), printed as rows of continuum_references.inc:
//   build/bin/test_engine -tc="continuum: every case*" --no-skip
TEST_CASE("continuum: every case of both halves" * doctest::skip()) {
    const bool resolve = std::getenv("BHM_CONTINUUM_RESOLVE") != nullptr;
    std::vector<std::string> all = kFittingHalf;
    all.insert(all.end(), kHeldOutHalf.begin(), kHeldOutHalf.end());
    double worst_fitting = 0.0, worst_held_out = 0.0;
    for (const std::string& name : all)
        for (double nu : {0.0, 0.35, 0.49}) {
            if (resolve) {
                const auto s = continuum_body(name, nu);
                const Measures two = fem_measures(s, 2), four = fem_measures(s, 4);
                std::printf("    {\"%s\", %.2f, %.5g, %.5g, %.5g, %.5g},\n", name.c_str(), nu,
                            two.tip * 1e3, two.com * 1e3, four.tip * 1e3, four.com * 1e3);
                continue;
            }
            const double worst = compare(name, nu);
            const bool fitting =
                std::find(kFittingHalf.begin(), kFittingHalf.end(), name) != kFittingHalf.end();
            (fitting ? worst_fitting : worst_held_out) =
                std::max(fitting ? worst_fitting : worst_held_out, worst);
        }
    if (!resolve)
        std::printf("worst: fitting half %.1f %%, held-out half %.1f %%\n", 100.0 * worst_fitting,
                    100.0 * worst_held_out);
}
