// The continuum suite of the shapes evolution makes (issue 40), first part: bodies held to the
// fixed face by 1, 2, 4 and 8 voxels (square, line and L-shaped patches, centred, at an edge and
// in a corner; since 2026-12-07 also one voxel and an upright pair at the side edge, whose held
// link gravity twists) and necks inside a body (1x1, 1x2, 2x1, 2x2), at nu 0, 0.35 and 0.49, at
// rest under gravity. Each body is a 6x4x4 block of E = 5 MPa from x = 1 to 6, and the x = 0 layer
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
#include <optional>
#include <set>
#include <string>
#include <utility>
#include <vector>

#include "calculix.hpp"
#include "evo/verify/ccx_deck.hpp"
#include "evo/verify/fem_model.hpp"
#include "evo/verify/quasi_static.hpp"
#include "richardson.hpp"
#include "support/ccx_skip.hpp"

using namespace bhm;

namespace {

// p1side and p2zside (2026-12-07, issue 40) were added to the split as new cases, one to each
// half: bodies held by one voxel (two upright) at the side edge of the face, 1.5 voxels off the
// body's centre line, so that gravity twists the held link as it does p1corner's.
const std::vector<std::string> kFittingHalf = {"p1c",     "p2y", "p4sq", "p4liney", "neck1",
                                               "neck2x2", "p8",  "full", "p1side"};
const std::vector<std::string> kHeldOutHalf = {"p1e",     "p1corner", "p2z",     "p2ye",
                                               "p4sqe",   "p4L",      "p4linez", "p8z",
                                               "neck1x2", "neck2x1",  "p2zside"};

// The actuated variant's expansion per degree: a 1 % strain at the +1 degree step, small enough
// for linear statics (the 6x4x4 block bends by about a degree).
constexpr double kActiveStrainPerC = 0.01;

// Every case's body: nx = 7, ny = nz = 4, voxel 0.01 m, E 5 MPa, density 1000, no floor. With
// `actuated`, the upper half (z >= 2) of every free voxel, narrow part included, is a second
// material of the same E and nu that expands by kActiveStrainPerC per degree.
engine::BodySpec continuum_body(const std::string& name, double nu, bool actuated = false) {
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
    else if (name == "p1side")
        rect(0, 0, 1, 1);
    else if (name == "p2zside")
        rect(0, 0, 1, 2);
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
    if (actuated) {
        engine::Material active = m;
        active.cte_per_c = kActiveStrainPerC;
        s.materials.push_back(active);
        for (int z = 2; z < s.nz; ++z)
            for (int y = 0; y < s.ny; ++y)
                for (int x = 1; x < s.nx; ++x)
                    if (s.material[s.cell_index(x, y, z)] != 0)
                        s.material[s.cell_index(x, y, z)] = 2;
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

Measures engine_measures(const engine::BodySpec& s, double temperature_c = 0.0) {
    const evo::QuasiStaticResult r = evo::engine_quasi_static(s, temperature_c);
    REQUIRE_MESSAGE(r.settled, r.problem);
    return measures(s, [&](int i) { return r.displacement_m[i][2]; });
}

// What the actuation adds: the displacement at +1 degree less the one at rest (gravity cancels).
Measures engine_actuation(const engine::BodySpec& s) {
    const Measures hot = engine_measures(s, 1.0), rest = engine_measures(s, 0.0);
    return {hot.tip - rest.tip, hot.com - rest.com};
}

// At rest, or (`actuated`) what the +1 degree step adds to the rest step.
Measures fem_measures(const engine::BodySpec& s, int subdivision, int threads = 2,
                      bool actuated = false) {
    evo::FemMeshOptions o;
    o.element = evo::FemElement::C3D20R;
    o.subdivision = subdivision;
    const evo::FemModel model = evo::build_fem_model(s, o);
    std::vector<evo::FemLoad> loads = {{"rest", 0.0}};
    if (actuated) loads.push_back({"+A", 1.0});
    const evo::CcxResult r =
        evo::run_ccx("continuum", evo::ccx_deck(model, s, loads, false), threads);
    REQUIRE(r.blocks.size() == loads.size());
    const evo::NodalDisplacements& u = r.blocks.back();
    const evo::NodalDisplacements& u0 = r.blocks.front();
    return measures(s, [&](int i) {
        double z = 0.0;
        for (auto [node, weight] : model.voxel_centre[i])
            z += weight * (u.at(node)[2] - (actuated ? u0.at(node)[2] : 0.0));
        return z;
    });
}

struct Reference {
    const char* name;
    double nu;
    double tip2, com2, tip4, com4;  // mm, at 2 and at 4 elements per voxel edge
};

// CalculiX 2.20 (Debian calculix-ccx), computed 2026-12-04 by "continuum: references"; the rows
// of p1side and p2zside 2026-12-07 by "continuum: every case of both halves" with
// BHM_CONTINUUM_RESOLVE=1 BHM_CONTINUUM_CASES=p1side,p2zside (one ccx thread, 15 minutes).
const Reference kReferences[] = {
#include "continuum_references.inc"
};

const Reference& reference(const std::string& name, double nu) {
    for (const Reference& r : kReferences)
        if (name == r.name && std::abs(nu - r.nu) < 1e-9) return r;
    FAIL("no reference for " << name << " at nu " << nu);
    return kReferences[0];
}

// The third mesh (6 elements per voxel edge) of the held-out cases furthest from the engine,
// CalculiX 2.20, 2026-12-06 ("continuum: third mesh of named cases"; 6-10 minutes each), of
// the fitting twisted case p1side at nu 0.35 (2026-12-07, 40 minutes on a shared core), and of
// the one-voxel patches p1corner, p1c and p1side at every nu (2026-12-08, 9-12 minutes each on a
// shared core, 5.0 GB peak): whether their nu 0.35 "bump" is the references' own error (it is not;
// docs/physics.md, "The held patches' nu 0.35 bump against converged references").
struct SixthReference {
    const char* name;
    double nu;
    double tip6, com6;  // mm
};
const SixthReference kSixthReferences[] = {
#include "continuum_references_six.inc"
};

// Richardson's limit through the meshes of h = 1/2, 1/4, 1/6 (richardson.hpp); nullopt where the
// three are not monotone.
std::optional<double> richardson_limit(double f2, double f4, double f6) {
    const double h[3] = {0.5, 0.25, 1.0 / 6.0}, f[3] = {f2, f4, f6};
    const auto extrapolated = bhm::test::richardson(h, f);
    if (!extrapolated) return std::nullopt;
    return extrapolated->limit;
}

// Prints "case nu ours / CalculiX (uncertainty) difference" and returns the worst difference.
// `actuated_body`: the engine solves the actuated variant (active upper half, same E and nu) at
// rest, against the one-material body's reference: the two are one body in the continuum.
double compare(const std::string& name, double nu, bool actuated_body = false) {
    const Reference& r = reference(name, nu);
    const Measures ours = engine_measures(continuum_body(name, nu, actuated_body));
    const double tip = ours.tip * 1e3 / r.tip4 - 1.0, com = ours.com * 1e3 / r.com4 - 1.0;
    std::printf(
        "%-9s nu %.2f  tip %8.4f / %8.4f mm (+-%4.1f %%) %+6.1f %%   com %8.4f / %8.4f mm "
        "(+-%4.1f %%) %+6.1f %%\n",
        name.c_str(), nu, ours.tip * 1e3, r.tip4, 100.0 * std::abs(r.tip4 / r.tip2 - 1.0),
        100.0 * tip, ours.com * 1e3, r.com4, 100.0 * std::abs(r.com4 / r.com2 - 1.0), 100.0 * com);
    for (const SixthReference& six : kSixthReferences) {
        if (name != six.name || std::abs(nu - six.nu) > 1e-9) continue;
        const auto tip_limit = richardson_limit(r.tip2, r.tip4, six.tip6);
        const auto com_limit = richardson_limit(r.com2, r.com4, six.com6);
        if (!tip_limit || !com_limit) continue;
        std::printf(
            "%-9s          limit of 2/4/6 per edge: tip %8.4f mm (+-%4.1f %%) %+6.1f %%   "
            "com %8.4f mm (+-%4.1f %%) %+6.1f %%\n",
            "", *tip_limit, 100.0 * std::abs(*tip_limit / six.tip6 - 1.0),
            100.0 * (ours.tip * 1e3 / *tip_limit - 1.0), *com_limit,
            100.0 * std::abs(*com_limit / six.com6 - 1.0),
            100.0 * (ours.com * 1e3 / *com_limit - 1.0));
    }
    return std::max(std::abs(tip), std::abs(com));
}

const Reference kActuatedReferences[] = {
#include "continuum_actuated_references.inc"
};

// As compare, for what the 1 % expansion of the upper half adds (continuum_body's `actuated`);
// returns the worst difference, or -1 where the case has no actuated reference yet.
double compare_actuated(const std::string& name, double nu) {
    const Reference* r = nullptr;
    for (const Reference& a : kActuatedReferences)
        if (name == a.name && std::abs(nu - a.nu) < 1e-9) r = &a;
    if (r == nullptr) return -1.0;
    const Measures ours = engine_actuation(continuum_body(name, nu, true));
    const double tip = ours.tip * 1e3 / r->tip4 - 1.0, com = ours.com * 1e3 / r->com4 - 1.0;
    std::printf(
        "%-9s nu %.2f  actuated: tip %8.4f / %8.4f mm (+-%4.1f %%) %+6.1f %%   com %8.4f / %8.4f "
        "mm (+-%4.1f %%) %+6.1f %%\n",
        name.c_str(), nu, ours.tip * 1e3, r->tip4, 100.0 * std::abs(r->tip4 / r->tip2 - 1.0),
        100.0 * tip, ours.com * 1e3, r->com4, 100.0 * std::abs(r->com4 / r->com2 - 1.0),
        100.0 * com);
    return std::max(std::abs(tip), std::abs(com));
}

// "a,b,c" (BHM_CONTINUUM_CASES and the other list variables) as a list of its items.
std::vector<std::string> case_list(const std::string& list) {
    std::vector<std::string> names;
    std::string rest = list;
    while (!rest.empty()) {
        const std::size_t comma = rest.find(',');
        names.push_back(rest.substr(0, comma));
        rest = comma == std::string::npos ? "" : rest.substr(comma + 1);
    }
    return names;
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
// The target is 5 % at any nu. The held-out necks hold it since their ends take the
// lateral stress form (link_confinement.hpp; worst 3.6 %, they were 6.3 / 13.8 / 8.2 % at nu 0 /
// 0.35 / 0.49); the held patches keep the envelope below: worst 8.6 / 10.5 / 9.9 % at nu 0 / 0.35
// / 0.49 (docs/physics.md lists the open cases: held patches at nu 0 stiff; 2-voxel-tall stalks
// at nu 0.49 were -19 % with the equal split of links of one material). p2zside, held out since
// 2026-12-07, is -1.1 / -3.2, +5.5 / +1.7, +1.9 / -3.6 % (tip / com at nu 0 / 0.35 / 0.49); the
// torsion of a held link, which it and p1corner load, is measured in docs/physics.md ("The
// torsion of a held link").
TEST_CASE("continuum: held-out attachments and necks against CalculiX at nu 0, 0.35, 0.49") {
    for (const std::string& name : kHeldOutHalf)
        for (double nu : {0.0, 0.35, 0.49}) {
            CAPTURE(name);
            CAPTURE(nu);
            const bool neck = name.starts_with("neck");
            const double tolerance = neck ? 0.05 : nu == 0.0 ? 0.10 : 0.11;
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
// edge (one ccx thread; about an hour on one core, BHM_CONTINUUM_CASES=a,b for a few), printed as
// rows of continuum_references.inc:
//   build/bin/test_engine -tc="continuum: every case*" --no-skip
// With BHM_CONTINUUM_ACTUATED_REST=1 the engine solves each case's actuated variant at rest (its
// active and passive halves are one material at rest), against the same references.
TEST_CASE("continuum: every case of both halves" * doctest::skip()) {
    const bool resolve = std::getenv("BHM_CONTINUUM_RESOLVE") != nullptr;
    const bool actuated_body = std::getenv("BHM_CONTINUUM_ACTUATED_REST") != nullptr;
    std::vector<std::string> all = kFittingHalf;
    all.insert(all.end(), kHeldOutHalf.begin(), kHeldOutHalf.end());
    if (const char* list = std::getenv("BHM_CONTINUUM_CASES")) all = case_list(list);
    double worst_fitting = 0.0, worst_held_out = 0.0;
    for (const std::string& name : all)
        for (double nu : {0.0, 0.35, 0.49}) {
            if (resolve) {
                const auto s = continuum_body(name, nu);
                const Measures two = fem_measures(s, 2, 1), four = fem_measures(s, 4, 1);
                std::printf("    {\"%s\", %.2f, %.5g, %.5g, %.5g, %.5g},\n", name.c_str(), nu,
                            two.tip * 1e3, two.com * 1e3, four.tip * 1e3, four.com * 1e3);
                std::fflush(stdout);
                continue;
            }
            const double worst = compare(name, nu, actuated_body);
            const bool fitting =
                std::find(kFittingHalf.begin(), kFittingHalf.end(), name) != kFittingHalf.end();
            (fitting ? worst_fitting : worst_held_out) =
                std::max(fitting ? worst_fitting : worst_held_out, worst);
        }
    if (!resolve)
        std::printf("worst: fitting half %.1f %%, held-out half %.1f %%\n", 100.0 * worst_fitting,
                    100.0 * worst_held_out);
}

// The third mesh, 6 elements per voxel edge (the next even subdivision: an odd one clamps
// elsewhere), for the cases named in BHM_CONTINUUM_SIX ("p2z@0.49,neck2x1@0.49"), one ccx thread:
// about 6 minutes and 9 GB each. Prints rows of continuum_references_six.inc.
TEST_CASE("continuum: third mesh of named cases" * doctest::skip()) {
    const char* list = std::getenv("BHM_CONTINUUM_SIX");
    REQUIRE_MESSAGE(list != nullptr, "set BHM_CONTINUUM_SIX=name@nu,...");
    for (const std::string& item : case_list(list)) {
        const std::size_t at = item.find('@');
        REQUIRE(at != std::string::npos);
        const std::string name = item.substr(0, at);
        const double nu = std::stod(item.substr(at + 1));
        const Measures six = fem_measures(continuum_body(name, nu), 6, 1);
        std::printf("    {\"%s\", %.2f, %.5g, %.5g},\n", name.c_str(), nu, six.tip * 1e3,
                    six.com * 1e3);
        std::fflush(stdout);
    }
}

// The actuated references (continuum_actuated_references.inc): what a 1 % expansion of the upper
// half adds, at 2 and 4 elements per voxel edge, for the held-out half and the full face, and
// since 2026-12-07 the fitting necks (neck1, neck2x2: BHM_CONTINUUM_CASES=neck1,neck2x2, 35 minutes
// on a shared core) and the twisted cases p1side and p2zside (BHM_CONTINUUM_CASES=p1side,p2zside,
// 35 minutes on a shared core) (the constants are fitted at rest only, so every actuated case is
// held out). About 40 minutes on one core:
//   BHM_CONTINUUM_RESOLVE=1 build/bin/test_engine -tc="continuum: actuated references" --no-skip
// BHM_CONTINUUM_CASES="full,p2z" solves those instead.
TEST_CASE("continuum: actuated references" * doctest::skip()) {
    std::vector<std::string> names = kHeldOutHalf;
    if (const char* list = std::getenv("BHM_CONTINUUM_CASES")) names = case_list(list);
    for (const std::string& name : names)
        for (double nu : {0.0, 0.35, 0.49}) {
            const auto s = continuum_body(name, nu, true);
            const Measures two = fem_measures(s, 2, 1, true), four = fem_measures(s, 4, 1, true);
            std::printf("    {\"%s\", %.2f, %.5g, %.5g, %.5g, %.5g},\n", name.c_str(), nu,
                        two.tip * 1e3, two.com * 1e3, four.tip * 1e3, four.com * 1e3);
            std::fflush(stdout);
        }
}

// Under a small actuation (the constants were fitted at rest, so every actuated case is held out):
// the cases whose references are stored, printed with --no-skip=... -s.
TEST_CASE("continuum: held-out bodies under a small actuation" * doctest::skip()) {
    int compared = 0;
    double worst = 0.0;
    std::vector<std::string> all = kFittingHalf;
    all.insert(all.end(), kHeldOutHalf.begin(), kHeldOutHalf.end());
    for (const std::string& name : all)
        for (double nu : {0.0, 0.35, 0.49}) {
            const double d = compare_actuated(name, nu);
            if (d < 0.0) continue;
            ++compared;
            worst = std::max(worst, d);
        }
    std::printf("actuated: %d cases, worst %.1f %%\n", compared, 100.0 * worst);
    CHECK(compared > 0);
}

// A link between an active voxel and a passive one splits its strain by stress continuity
// (engine/internal/poisson.cpp, same_free_strain; docs/physics.md "Actuated narrow parts"). With
// the equal split the passive half shared the active half's thinning, and where that passive voxel
// held a narrow part the Poisson coupling turned it: at 0508944 a 2-voxel-tall stalk moved
// +84 / +110 % (tip / com) too far at nu 0.49, a 2x1 neck +48 %, an L of 4 +39 %, a 2x2 patch at
// the bottom edge -136 %. Nothing in the change is fitted, so every case here is held out. The
// bounds are today's envelope (the target is 5 %; the one-voxel-tall patches at the bottom
// edge, p1e and p2ye, are 31-44 % off on the tip, most of it the lattice's resolution: on the same
// engine 3 times finer, "continuum: refined by an odd factor", they are within 4.4-9.5 %). The 2x1
// neck holds 5 % since the neck ends' lateral stress form (it was 9.3 %), the 2x2 neck 6.5 % (was
// 11.2 %); the 1x1 and 1x2 necks, one voxel tall under the active layer, whose error at nu 0 no
// confinement moves (-22 / -23 % on the tip; the 1x2 neck -7..-9 % on the lattice refined
// 2 x 2 x 2), are kept at their envelope.
TEST_CASE("continuum: actuated narrow parts against CalculiX (active and passive halves split)") {
    struct Bound {
        const char* name;
        double worst;  // of tip and com, at nu 0.35 and 0.49
    };
    for (const Bound& b : {Bound{"full", 0.10}, Bound{"neck2x1", 0.05}, Bound{"neck2x2", 0.07},
                           Bound{"neck1", 0.20}, Bound{"neck1x2", 0.20}, Bound{"p4L", 0.10},
                           Bound{"p8z", 0.15}, Bound{"p2z", 0.30}, Bound{"p4sqe", 0.35}})
        for (double nu : {0.35, 0.49}) {
            CAPTURE(b.name);
            CAPTURE(nu);
            const double d = compare_actuated(b.name, nu);
            REQUIRE(d >= 0.0);
            CHECK(d <= b.worst);
        }
}

namespace {

// Per x layer of the body: the mean vertical displacement (m) of its voxel centres and its tilt
// about y (rad, from the layer's x displacements against height; 0 for a one-voxel-tall layer).
struct LayerProfile {
    std::vector<double> uz, tilt;
};

template <class UOf>
LayerProfile layer_profile(const engine::BodySpec& s, UOf u_of) {
    LayerProfile p;
    p.uz.assign(s.nx, 0.0);
    p.tilt.assign(s.nx, 0.0);
    std::vector<double> n(s.nx, 0.0), sz(s.nx, 0.0), szz(s.nx, 0.0), sx(s.nx, 0.0), sxz(s.nx, 0.0);
    int i = 0;
    for (int c = 0; c < s.cell_count(); ++c) {
        if (s.material[c] == 0) continue;
        const std::array<double, 3> u = u_of(i++);
        const int x = c % s.nx;
        const double z = (c / (s.nx * s.ny)) * s.voxel_size_m;
        n[x] += 1.0;
        p.uz[x] += u[2];
        sz[x] += z;
        szz[x] += z * z;
        sx[x] += u[0];
        sxz[x] += u[0] * z;
    }
    for (int x = 0; x < s.nx; ++x) {
        p.uz[x] /= n[x];
        const double var = szz[x] / n[x] - (sz[x] / n[x]) * (sz[x] / n[x]);
        // A rotation theta about y moves x by +theta z: the slope of u_x against z.
        if (var > 1e-12) p.tilt[x] = (sxz[x] / n[x] - sx[x] / n[x] * sz[x] / n[x]) / var;
    }
    return p;
}

}  // namespace

// Where the actuated narrow bodies differ from CalculiX (issue 40): per x layer, what the 1 %
// expansion of the upper half adds to the mean vertical displacement (um) and to the tilt about y
// (mrad), the engine's against CalculiX at BHM_CONTINUUM_SUBDIVISION (default 2) elements per voxel
// edge, for the cases in BHM_CONTINUUM_CASES (default p1e,p2z,p4sqe,neck1x2,neck2x1,full) at
// nu 0, 0.35, 0.49. A layer's tilt against the one before shows where the bending happens:
//   build/bin/test_engine -tc="continuum: actuated layer profiles" --no-skip
TEST_CASE("continuum: actuated layer profiles" * doctest::skip()) {
    if (bhm::test::skip_without_ccx()) return;
    std::vector<std::string> names = {"p1e", "p2z", "p4sqe", "neck1x2", "neck2x1", "full"};
    if (const char* list = std::getenv("BHM_CONTINUUM_CASES")) names = case_list(list);
    const char* sub = std::getenv("BHM_CONTINUUM_SUBDIVISION");
    const int subdivision = sub != nullptr ? std::atoi(sub) : 2;
    for (const std::string& name : names)
        for (double nu : {0.0, 0.35, 0.49}) {
            const auto s = continuum_body(name, nu, true);
            const evo::QuasiStaticResult hot = evo::engine_quasi_static(s, 1.0),
                                         cold = evo::engine_quasi_static(s, 0.0);
            REQUIRE(hot.settled);
            REQUIRE(cold.settled);
            const LayerProfile ours = layer_profile(s, [&](int i) {
                std::array<double, 3> u;
                for (int a = 0; a < 3; ++a)
                    u[a] = hot.displacement_m[i][a] - cold.displacement_m[i][a];
                return u;
            });
            evo::FemMeshOptions o;
            o.element = evo::FemElement::C3D20R;
            o.subdivision = subdivision;
            const evo::FemModel model = evo::build_fem_model(s, o);
            const std::vector<evo::FemLoad> loads = {{"rest", 0.0}, {"+A", 1.0}};
            const evo::CcxResult r =
                evo::run_ccx("continuum", evo::ccx_deck(model, s, loads, false), 2);
            REQUIRE(r.blocks.size() == 2);
            const LayerProfile fem = layer_profile(s, [&](int i) {
                std::array<double, 3> u{};
                for (auto [node, weight] : model.voxel_centre[i])
                    for (int a = 0; a < 3; ++a)
                        u[a] += weight * (r.blocks[1].at(node)[a] - r.blocks[0].at(node)[a]);
                return u;
            });
            std::printf("%-8s nu %.2f  uz (um) ours/fem, tilt (mrad) ours/fem per layer:\n",
                        name.c_str(), nu);
            for (int x = 0; x < s.nx; ++x)
                std::printf("   x %d  uz %8.2f / %8.2f   tilt %7.3f / %7.3f\n", x, 1e6 * ours.uz[x],
                            1e6 * fem.uz[x], 1e3 * ours.tilt[x], 1e3 * fem.tilt[x]);
            std::fflush(stdout);
        }
}

namespace {

// The body with every voxel split into 2 x 2 x 2 of half the size. A held voxel's clamp is the
// plane through its centre, which in the refined lattice lies between the two sub-layers of the
// held layer: `hold_both` holds both (the clamp half a sub-voxel beyond the coarse one's, the
// narrow part shorter by a quarter voxel), otherwise only the outer one (longer by a quarter).
engine::BodySpec refined_body(const engine::BodySpec& s, bool hold_both) {
    engine::BodySpec r = s;
    r.nx = 2 * s.nx;
    r.ny = 2 * s.ny;
    r.nz = 2 * s.nz;
    r.voxel_size_m = 0.5 * s.voxel_size_m;
    r.material.assign(r.cell_count(), 0);
    r.fixed.assign(r.cell_count(), 0);
    for (int z = 0; z < r.nz; ++z)
        for (int y = 0; y < r.ny; ++y)
            for (int x = 0; x < r.nx; ++x) {
                const int c = s.cell_index(x / 2, y / 2, z / 2);
                r.material[r.cell_index(x, y, z)] = s.material[c];
                r.fixed[r.cell_index(x, y, z)] =
                    s.fixed.empty() ? 0 : (s.fixed[c] != 0 && (hold_both || x % 2 == 0));
            }
    return r;
}

// The coarse measures from the refined answer: a coarse voxel's centre moves as the mean of its
// eight sub-voxels.
Measures refined_actuation(const engine::BodySpec& coarse, bool hold_both) {
    const engine::BodySpec r = refined_body(coarse, hold_both);
    const evo::QuasiStaticResult hot = evo::engine_quasi_static(r, 1.0),
                                 cold = evo::engine_quasi_static(r, 0.0);
    REQUIRE_MESSAGE(hot.settled, hot.problem);
    REQUIRE_MESSAGE(cold.settled, cold.problem);
    std::vector<double> dz(coarse.cell_count(), 0.0);
    int i = 0;
    for (int c = 0; c < r.cell_count(); ++c) {
        if (r.material[c] == 0) continue;
        const int x = c % r.nx, y = (c / r.nx) % r.ny, z = c / (r.nx * r.ny);
        dz[coarse.cell_index(x / 2, y / 2, z / 2)] +=
            (hot.displacement_m[i][2] - cold.displacement_m[i][2]) / 8.0;
        ++i;
    }
    std::vector<double> by_voxel;
    for (int c = 0; c < coarse.cell_count(); ++c)
        if (coarse.material[c] != 0) by_voxel.push_back(dz[c]);
    return measures(coarse, [&](int j) { return by_voxel[j]; });
}

}  // namespace

// Whether the actuated narrow bodies' error is the lattice's resolution (issue 40): the engine on
// the same bodies with every voxel split in eight, against the stored 4-per-edge references, for
// BHM_CONTINUUM_CASES (default p1e,p2z,p4sqe,neck1x2,neck2x1,full) at nu 0, 0.35, 0.49, with the
// refined clamp a quarter voxel either side of the coarse one (a few seconds per run):
//   build/bin/test_engine -tc="continuum: actuated on a refined lattice" --no-skip
TEST_CASE("continuum: actuated on a refined lattice" * doctest::skip()) {
    std::vector<std::string> names = {"p1e", "p2z", "p4sqe", "neck1x2", "neck2x1", "full"};
    if (const char* list = std::getenv("BHM_CONTINUUM_CASES")) names = case_list(list);
    for (const std::string& name : names)
        for (double nu : {0.0, 0.35, 0.49}) {
            const Reference* ref = nullptr;
            for (const Reference& a : kActuatedReferences)
                if (name == a.name && std::abs(nu - a.nu) < 1e-9) ref = &a;
            if (ref == nullptr) continue;
            const auto s = continuum_body(name, nu, true);
            const Measures coarse = engine_actuation(s);
            const Measures outer = refined_actuation(s, false), both = refined_actuation(s, true);
            auto pct = [](double ours_m, double ref_mm) {
                return 100.0 * (ours_m * 1e3 / ref_mm - 1.0);
            };
            std::printf(
                "%-8s nu %.2f  tip / com vs CalculiX: coarse %+6.1f / %+6.1f %%, refined "
                "(outer held) %+6.1f / %+6.1f %%, refined (both held) %+6.1f / %+6.1f %%\n",
                name.c_str(), nu, pct(coarse.tip, ref->tip4), pct(coarse.com, ref->com4),
                pct(outer.tip, ref->tip4), pct(outer.com, ref->com4), pct(both.tip, ref->tip4),
                pct(both.com, ref->com4));
            std::fflush(stdout);
        }
}

// Where an actuated body's strain differs from CalculiX's, voxel by voxel (issue 40): for one case
// (BHM_CONTINUUM_CASES, default p4sqe) at BHM_NU (default 0.49), the x layers 0-3 of the row
// y = BHM_Y (default 1), what the 1 % expansion adds to each voxel centre's normal strains (central
// differences of the centres' displacements) and to its x displacement, ours / CalculiX at 2
// elements per voxel edge (a few seconds):
//   build/bin/test_engine -tc="continuum: actuated strain map" --no-skip
TEST_CASE("continuum: actuated strain map" * doctest::skip()) {
    if (bhm::test::skip_without_ccx()) return;
    const char* list = std::getenv("BHM_CONTINUUM_CASES");
    std::string name = list ? list : "p4sqe";
    const char* nus = std::getenv("BHM_NU");
    const double nu = nus ? std::atof(nus) : 0.49;
    const auto s = continuum_body(name, nu, true);
    const evo::QuasiStaticResult hot = evo::engine_quasi_static(s, 1.0),
                                 cold = evo::engine_quasi_static(s, 0.0);
    REQUIRE(hot.settled);
    std::vector<std::array<double, 3>> ours(s.cell_count()), fem(s.cell_count());
    std::vector<int> idx(s.cell_count(), -1);
    int i = 0;
    for (int c = 0; c < s.cell_count(); ++c)
        if (s.material[c] != 0) idx[c] = i++;
    evo::FemMeshOptions o;
    o.element = evo::FemElement::C3D20R;
    o.subdivision = 2;
    const evo::FemModel model = evo::build_fem_model(s, o);
    const std::vector<evo::FemLoad> loads = {{"rest", 0.0}, {"+A", 1.0}};
    const evo::CcxResult r = evo::run_ccx("continuum", evo::ccx_deck(model, s, loads, false), 2);
    for (int c = 0; c < s.cell_count(); ++c) {
        if (idx[c] < 0) continue;
        for (int a = 0; a < 3; ++a) {
            ours[c][a] = hot.displacement_m[idx[c]][a] - cold.displacement_m[idx[c]][a];
            double u = 0;
            for (auto [node, weight] : model.voxel_centre[idx[c]])
                u += weight * (r.blocks[1].at(node)[a] - r.blocks[0].at(node)[a]);
            fem[c][a] = u;
        }
    }
    const double L = s.voxel_size_m;
    auto strain = [&](const std::vector<std::array<double, 3>>& u, int x, int y, int z, int a) {
        int p[3] = {x, y, z}, m[3] = {x, y, z};
        p[a] += 1;
        m[a] -= 1;
        const int n[3] = {s.nx, s.ny, s.nz};
        auto ok = [&](int* q) {
            return q[a] >= 0 && q[a] < n[a] && idx[s.cell_index(q[0], q[1], q[2])] >= 0;
        };
        const int c = s.cell_index(x, y, z);
        if (ok(p) && ok(m))
            return (u[s.cell_index(p[0], p[1], p[2])][a] - u[s.cell_index(m[0], m[1], m[2])][a]) /
                   (2 * L);
        if (ok(p)) return (u[s.cell_index(p[0], p[1], p[2])][a] - u[c][a]) / L;
        if (ok(m)) return (u[c][a] - u[s.cell_index(m[0], m[1], m[2])][a]) / L;
        return 0.0;
    };
    const char* ys = std::getenv("BHM_Y");
    const int y = ys ? std::atoi(ys) : 1;
    std::printf("%s nu %.2f y %d: per voxel x,z: ex ours/fem  ey ours/fem  ez ours/fem (1e-3)\n",
                name.c_str(), nu, y);
    for (int x = 0; x < 4; ++x)
        for (int z = 0; z < s.nz; ++z) {
            if (idx[s.cell_index(x, y, z)] < 0) continue;
            std::printf(
                "  x %d z %d  ex %6.2f / %6.2f  ey %6.2f / %6.2f  ez %6.2f / %6.2f  ux %6.2f / "
                "%6.2f um\n",
                x, z, 1e3 * strain(ours, x, y, z, 0), 1e3 * strain(fem, x, y, z, 0),
                1e3 * strain(ours, x, y, z, 1), 1e3 * strain(fem, x, y, z, 1),
                1e3 * strain(ours, x, y, z, 2), 1e3 * strain(fem, x, y, z, 2),
                1e6 * ours[s.cell_index(x, y, z)][0], 1e6 * fem[s.cell_index(x, y, z)][0]);
        }
}

namespace {

// The body with every voxel split into k x k x k of 1 / k the size, k odd (issue 40, patch40). A
// held voxel's clamp is the plane through its centre, which for odd k is the centre plane of its
// middle sub-layer: that sub-layer is held, the sub-layers beyond the clamp are left out (the
// continuum model has no material there) and those toward the body are free, the half-voxel
// stalk of the coarse held voxel. So the refined body is the same continuum body as the coarse
// one, clamp included (refined_body's even split cannot put a clamp there). Only held voxels at
// the lattice's x = 0 face are refined so (every continuum case's).
engine::BodySpec refined_body_odd(const engine::BodySpec& s, int k) {
    engine::BodySpec r = s;
    r.nx = k * s.nx;
    r.ny = k * s.ny;
    r.nz = k * s.nz;
    r.voxel_size_m = s.voxel_size_m / k;
    r.material.assign(r.cell_count(), 0);
    r.fixed.assign(r.cell_count(), 0);
    const int middle = k / 2;
    for (int z = 0; z < r.nz; ++z)
        for (int y = 0; y < r.ny; ++y)
            for (int x = 0; x < r.nx; ++x) {
                const int c = s.cell_index(x / k, y / k, z / k);
                const bool held = !s.fixed.empty() && s.fixed[c] != 0;
                if (held) REQUIRE(x / k == 0);
                if (held && x % k < middle) continue;
                r.material[r.cell_index(x, y, z)] = s.material[c];
                r.fixed[r.cell_index(x, y, z)] = held && x % k == middle;
            }
    return r;
}

// The coarse measures (rest, or what the +1 degree step adds) from the refined answer: a coarse
// voxel's centre is its middle sub-voxel's centre.
Measures refined_odd_measures(const engine::BodySpec& coarse, int k, bool actuated) {
    const engine::BodySpec r = refined_body_odd(coarse, k);
    const evo::QuasiStaticResult hot = evo::engine_quasi_static(r, actuated ? 1.0 : 0.0);
    REQUIRE_MESSAGE(hot.settled, hot.problem);
    std::vector<int> index(r.cell_count(), -1);
    int i = 0;
    for (int c = 0; c < r.cell_count(); ++c)
        if (r.material[c] != 0) index[c] = i++;
    evo::QuasiStaticResult cold;
    if (actuated) {
        cold = evo::engine_quasi_static(r, 0.0);
        REQUIRE_MESSAGE(cold.settled, cold.problem);
    }
    std::vector<double> by_voxel;
    const int middle = k / 2;
    for (int c = 0; c < coarse.cell_count(); ++c) {
        if (coarse.material[c] == 0) continue;
        const int x = c % coarse.nx, y = (c / coarse.nx) % coarse.ny,
                  z = c / (coarse.nx * coarse.ny);
        const int j = index[r.cell_index(k * x + middle, k * y + middle, k * z + middle)];
        REQUIRE(j >= 0);
        by_voxel.push_back(hot.displacement_m[j][2] - (actuated ? cold.displacement_m[j][2] : 0.0));
    }
    return measures(coarse, [&](int j) { return by_voxel[j]; });
}

}  // namespace

// Whether an error is the lattice's resolution (issue 40, patch40): the engine on the same
// continuum body refined by an odd factor k (BHM_CONTINUUM_FACTOR, default 3; the clamp where the
// coarse body's is), against the same stored 4-per-edge CalculiX references, for
// BHM_CONTINUUM_CASES (default p1e,p2ye,p1corner,p1c) at BHM_NUS (default 0,0.35,0.49), at rest
// and under the small actuation (BHM_CONTINUUM_LOADS=rest,actuated). k = 3 is 27x the voxels and
// a third of the step: about 20-60 s per solve.
//   BHM_CONTINUUM_FACTOR=3 build/bin/test_engine -tc="continuum: refined by an odd factor"
//   --no-skip
TEST_CASE("continuum: refined by an odd factor" * doctest::skip()) {
    auto list = [](const char* variable, const char* fallback) {
        const char* value = std::getenv(variable);
        return case_list(value != nullptr ? value : fallback);
    };
    const std::vector<std::string> names = list("BHM_CONTINUUM_CASES", "p1e,p2ye,p1corner,p1c");
    const std::vector<std::string> nus = list("BHM_NUS", "0,0.35,0.49");
    const std::vector<std::string> loads = list("BHM_CONTINUUM_LOADS", "rest,actuated");
    const char* factor = std::getenv("BHM_CONTINUUM_FACTOR");
    const int k = factor != nullptr ? std::atoi(factor) : 3;
    REQUIRE(k % 2 == 1);
    for (const std::string& load : loads)
        for (const std::string& name : names)
            for (const std::string& nu_text : nus) {
                const double nu = std::stod(nu_text);
                const bool actuated = load == "actuated";
                const Reference* ref = nullptr;
                if (actuated) {
                    for (const Reference& a : kActuatedReferences)
                        if (name == a.name && std::abs(nu - a.nu) < 1e-9) ref = &a;
                } else {
                    ref = &reference(name, nu);
                }
                if (ref == nullptr) continue;
                const auto s = continuum_body(name, nu, actuated);
                const Measures coarse = actuated ? engine_actuation(s) : engine_measures(s);
                const Measures fine = refined_odd_measures(s, k, actuated);
                auto pct = [](double ours_m, double ref_mm) {
                    return 100.0 * (ours_m * 1e3 / ref_mm - 1.0);
                };
                std::printf(
                    "%-8s %-8s nu %.2f  tip / com vs CalculiX: coarse %+6.1f / %+6.1f %%, "
                    "refined %dx %+6.1f / %+6.1f %%\n",
                    name.c_str(), load.c_str(), nu, pct(coarse.tip, ref->tip4),
                    pct(coarse.com, ref->com4), k, pct(fine.tip, ref->tip4),
                    pct(fine.com, ref->com4));
                std::fflush(stdout);
            }
}
