// Bodies of two materials against CalculiX (issue 24): stiffness contrasts of 10 and 100 at
// nu 0, 0.35 and 0.49 on the layered cantilever (both orders of its layers), a bilayer of soft
// active tissue on a stiff passive strip heated by 1 degC, a voxel checkerboard cantilever and a
// stiff-core / soft-shell beam under their own weight. Each scene is meshed voxel for voxel in
// CalculiX (C3D20R, the clamp at the held voxels' centre plane) and compared at the tip: the
// mean vertical displacement of the last voxel layer's centres.
// docs/physics.md ("Bodies of several materials") has the table these cases print.
#include <doctest/doctest.h>

#include "support/ccx_skip.hpp"

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <functional>
#include <map>
#include <numbers>
#include <sstream>
#include <string>
#include <vector>

#include "calculix.hpp"
#include "engine_test_bodies.hpp"

using namespace bhm::engine;
using namespace bhm::engine::test;

namespace {

constexpr double kL = 0.01;     // voxel size (m)
constexpr double kStiff = 5e6;  // the stiffer material's E (Pa); the softer is kStiff / contrast
constexpr double kCte = 0.01;   // active material, heated scenes (1 / degC)

enum class Load { Gravity, Heat };

// A clamped nx x ny x nz box whose voxel (x, y, z) is of material soft_or_stiff(x, y, z):
// 0 = soft (E / contrast), 1 = stiff (E). In heated scenes the soft material is the active one.
struct MixedScene {
    const char* name;
    int nx, ny, nz;
    Load load;
    std::function<int(int, int, int)> stiff;
};

// A number in [0, 1) fixed by a cell and a seed (splitmix64's finaliser over the packed cell).
double random_cell(int x, int y, int z, std::uint64_t seed) {
    std::uint64_t v = seed * 0x9E3779B97F4A7C15ull + (static_cast<std::uint64_t>(x) << 32) +
                      (static_cast<std::uint64_t>(y) << 16) + static_cast<std::uint64_t>(z);
    v = (v ^ (v >> 30)) * 0xBF58476D1CE4E5B9ull;
    v = (v ^ (v >> 27)) * 0x94D049BB133111EBull;
    v ^= v >> 31;
    return static_cast<double>(v >> 11) * 0x1.0p-53;
}

std::vector<MixedScene> mixed_scenes() {
    return {
        {"layers-stiff-in-soft", 20, 8, 7, Load::Gravity,
         [](int, int, int z) { return z == 1 || z == 5 ? 1 : 0; }},
        {"layers-soft-in-stiff", 20, 8, 7, Load::Gravity,
         [](int, int, int z) { return z == 1 || z == 5 ? 0 : 1; }},
        {"bilayer-soft-active", 20, 2, 4, Load::Heat,
         [](int, int, int z) { return z < 2 ? 0 : 1; }},
        {"checkerboard", 12, 4, 4, Load::Gravity,
         [](int x, int y, int z) { return (x + y + z) % 2; }},
        {"core-shell", 20, 4, 4, Load::Gravity,
         [](int, int y, int z) { return y >= 1 && y <= 2 && z >= 1 && z <= 2 ? 1 : 0; }},
        // Random mixtures (issue 40): each voxel stiff with probability one half (or 0.3), drawn
        // from a hash of its cell, so the body is the same on every machine.
        {"random50", 12, 4, 4, Load::Gravity,
         [](int x, int y, int z) { return random_cell(x, y, z, 1) < 0.5 ? 1 : 0; }},
        {"random30", 12, 4, 4, Load::Gravity,
         [](int x, int y, int z) { return random_cell(x, y, z, 2) < 0.3 ? 1 : 0; }},
        {"slices", 12, 4, 4, Load::Gravity, [](int x, int, int) { return x % 2; }},
        // A second 50/50 draw (seed 3), added after mixed_link_bending_factor was chosen while
        // looking at random50: the blind check of that form.
        {"random50b", 12, 4, 4, Load::Gravity,
         [](int x, int y, int z) { return random_cell(x, y, z, 3) < 0.5 ? 1 : 0; }},
    };
}

using bhm::test::skip_without_ccx;

std::vector<ccx::Material> materials(const MixedScene& s, double contrast, double nu) {
    const double cte = s.load == Load::Heat ? kCte : 0.0;
    return {{kStiff / contrast, nu, 1000.0, cte}, {kStiff, nu, 1000.0, 0.0}};
}

// CalculiX: elements of L / 2 along x from the clamp (voxel 0's centre), one element per voxel
// across; element ex lies in voxel (ex + 1) / 2.
// `refine` elements per voxel edge (2 refine along x) check the mesh's convergence.
ccx::Mesh calculix_mesh(const MixedScene& s, int refine) {
    const int r = refine;
    ccx::Mesh m{{(s.nx - 0.5) * kL, s.ny * kL, s.nz * kL},
                {r * (2 * s.nx - 1), r * s.ny, r * s.nz}};
    if (const char* q = std::getenv("BHM_GRADING")) {  // on demand (the probe below)
        m.grading = std::atof(q);
        m.voxel = kL;
        m.offset = {-0.5 * kL, 0.0, 0.0};
    }
    return m;
}

// Solves the scene on `m` (of calculix_mesh(s, refine)) and returns the displacements of the
// nodes `printed`.
std::map<int, std::array<double, 3>> calculix_solve(const MixedScene& s, double contrast, double nu,
                                                    int refine, const ccx::Mesh& m,
                                                    const std::vector<int>& printed) {
    const int r = refine;
    std::ostringstream inp;
    ccx::write_mesh(inp, m, materials(s, contrast, nu), [&](int ex, int ey, int ez) {
        return s.stiff((ex / r + 1) / 2, ey / r, ez / r);
    });
    ccx::write_set(inp, "NSET", "CLAMP",
                   ccx::nodes_where(m, [](double x, double, double) { return x < 1e-9; }));
    ccx::write_set(inp, "NSET", "PRINTED", printed);
    inp << "*BOUNDARY\nCLAMP, 1, 3\n";
    if (s.load == Load::Heat)
        inp << "*INITIAL CONDITIONS, TYPE=TEMPERATURE\nNALL, 0.\n*STEP\n*STATIC\n"
               "*TEMPERATURE\nNALL, 1.\n";
    else
        inp << "*STEP\n*STATIC\n*DLOAD\nEALL, GRAV, 9.81, 0., 0., -1.\n";
    inp << "*NODE PRINT, NSET=PRINTED\nU\n*END STEP\n";
    return ccx::solve(s.name, inp.str());
}

double calculix_tip(const MixedScene& s, double contrast, double nu, int refine = 1) {
    const ccx::Mesh m = calculix_mesh(s, refine);
    const double probe_x = (s.nx - 1) * kL;
    const auto probe = ccx::nodes_where(
        m, [&](double x, double, double) { return std::fabs(x - probe_x) < 1e-9; });
    return ccx::mean(calculix_solve(s, contrast, nu, refine, m, probe), probe, 2);
}

// Runs a world to static equilibrium (1e-4 relative change of the tip over 0.05 s slices).
double settle(World& w, int layer) {
    double last = 0.0;
    for (int slice = 1; slice <= 120; ++slice) {
        REQUIRE(w.advance_to(0.05 * slice));
        const double now = layer_displacement(w, layer, 2);
        if (slice > 2 && std::fabs(now - last) <= 1e-4 * std::fabs(now)) return now;
        last = now;
    }
    FAIL("did not reach static equilibrium");
    return last;
}

BodySpec engine_body(const MixedScene& s, double contrast, double nu) {
    const auto mats = materials(s, contrast, nu);
    Material soft;
    soft.youngs_modulus_pa = mats[0].e;
    soft.poisson_ratio = nu;
    soft.cte_per_c = mats[0].cte;
    Material stiff = soft;
    stiff.youngs_modulus_pa = mats[1].e;
    stiff.cte_per_c = 0.0;
    BodySpec b = solid_box(s.nx, s.ny, s.nz, soft);
    b.materials.push_back(stiff);
    for (int z = 0; z < s.nz; ++z)
        for (int y = 0; y < s.ny; ++y)
            for (int x = 0; x < s.nx; ++x)
                b.material[b.cell_index(x, y, z)] = static_cast<std::uint8_t>(1 + s.stiff(x, y, z));
    fix_x_min_layer(b);
    b.damping.bond_ratio = 0.1;
    b.damping.global_ratio = 0.05;
    if (s.load == Load::Heat) {
        // A constant +1 degC: frequency 0 and phase pi / 2 make dT = A sin(pi / 2) = A.
        b.actuation.frequency_hz = 0.0;
        b.actuation.temperature_amplitude_c = 1.0;
        b.actuation.start_s = 0.0;
        b.phase_rad.assign(b.material.size(), static_cast<float>(std::numbers::pi / 2));
    } else {
        b.environment.gravity_m_s2 = -9.81;
    }
    return b;
}

double engine_tip(const MixedScene& s, double contrast, double nu) {
    World w(Model::build(engine_body(s, contrast, nu)));
    return settle(w, s.nx - 1);
}

struct Result {
    double ours = 0.0, fem = 0.0;
    double error() const { return ours / fem - 1.0; }
};

Result compare(const MixedScene& s, double contrast, double nu) {
    Result r{engine_tip(s, contrast, nu), calculix_tip(s, contrast, nu)};
    MESSAGE(std::string(s.name) << ", contrast " << contrast << ", nu " << nu << ": tip " << r.ours
                                << " m, CalculiX " << r.fem << " m, error " << 100.0 * r.error()
                                << " %");
    return r;
}

const MixedScene& scene(const char* name) {
    static const std::vector<MixedScene> all = mixed_scenes();
    for (const MixedScene& s : all)
        if (std::string(s.name) == name) return s;
    throw std::runtime_error(std::string("no scene ") + name);
}

}  // namespace

static void check(const char* name, double contrast, double nu, double tolerance) {
    const Result r = compare(scene(name), contrast, nu);
    CHECK(std::fabs(r.error()) < tolerance);
}

// A few cells of the table below, seconds each (2-core machine, unloaded).
TEST_CASE("calculix: soft layers in a stiffer cantilever under gravity within 5%") {
    if (skip_without_ccx()) return;
    check("layers-soft-in-stiff", 10.0, 0.49, 0.05);
    check("layers-soft-in-stiff", 100.0, 0.49, 0.05);  // -2.8 %
    // The clamp's held voxels turning against their spring to the wall (model.cpp) brought these
    // two inside: -5.5 / -5.6 % with the clamp's rotation locked, -4.8 / -4.7 % now.
    check("layers-soft-in-stiff", 100.0, 0.0, 0.05);
    check("layers-soft-in-stiff", 100.0, 0.35, 0.05);
}

TEST_CASE("calculix: stiff layers in a 100x softer cantilever under gravity within 5%") {
    if (skip_without_ccx()) return;
    check("layers-stiff-in-soft", 100.0, 0.35, 0.05);
}

TEST_CASE("calculix: soft active tissue on a stiff passive strip heated 1 degC") {
    if (skip_without_ccx()) return;
    check("bilayer-soft-active", 10.0, 0.35, 0.05);
    check("bilayer-soft-active", 100.0, 0.35, 0.05);
    check("bilayer-soft-active", 10.0, 0.49, 0.05);   // -4.7 %; was -9.3 %
    check("bilayer-soft-active", 100.0, 0.49, 0.05);  // -2.4 %; was -12.5 %
}

TEST_CASE("calculix: a stiff-core / soft-shell beam under gravity") {
    if (skip_without_ccx()) return;
    check("core-shell", 10.0, 0.49, 0.05);
    check("core-shell", 100.0, 0.35, 0.05);  // -1.7 %; was -5.3 %
}

// Stiff voxels that touch only along edges, joined there by the springs across edges
// (engine/internal/edge_springs.hpp). The continuum converges slowly with the mesh here (the
// stress at two stiff cubes' shared edge is singular), so the reference is CalculiX at 2, 3 and 4
// elements per voxel extrapolated to zero element size (Richardson, with the order the three
// show). Those meshes take minutes and 5 GB each, so their tips are stored; regenerate with
//   BHM_SCENE=checkerboard BHM_CONTRAST=10 BHM_NU=0.35 BHM_REFINE=4
//     build/bin/test_engine -tc="calculix probe*" --no-skip
// The one-element tip is computed live and must equal the stored one: it ties the stored series
// to this deck. Contrasts above 10 do not settle at 4 elements per voxel (docs/physics.md).
namespace {

struct RefinedTips {
    double contrast, nu;
    double tip[4];  // m, 1 to 4 elements per voxel
};

constexpr RefinedTips kCheckerboardTips[] = {
    {3.0, 0.35, {-0.000588761, -0.000596614, -0.000598793, -0.000599783}},
    {10.0, 0.0, {-0.00108288, -0.00115632, -0.0011818, -0.0011962}},
    {10.0, 0.35, {-0.00110219, -0.00115489, -0.00117725, -0.00118989}},
    {10.0, 0.49, {-0.00091271, -0.00102981, -0.00105487, -0.00106772}},
};

// tip(r) = tip_0 - A r^-p through the tips at r = r0, r0 + 1, r0 + 2 elements per voxel: p from the
// ratio of the two differences (bisection; the ratio falls monotonically with p), then tip_0.
// Returns NaN where the three are not monotone in that way (no order in (0.05, 4) fits them).
double extrapolated_tip(double t_a, double t_b, double t_c, int r0) {
    const double ratio = (t_c - t_b) / (t_b - t_a);
    const double ra = r0, rb = r0 + 1, rc = r0 + 2;
    auto ratio_at = [&](double p) {
        return (std::pow(rb, -p) - std::pow(rc, -p)) / (std::pow(ra, -p) - std::pow(rb, -p));
    };
    double lo = 0.05, hi = 4.0;
    if (!(ratio < ratio_at(lo) && ratio > ratio_at(hi))) return std::nan("");
    for (int i = 0; i < 60; ++i) {
        const double mid = 0.5 * (lo + hi);
        (ratio_at(mid) > ratio ? lo : hi) = mid;
    }
    const double p = 0.5 * (lo + hi);
    const double amplitude = (t_c - t_b) / (std::pow(rb, -p) - std::pow(rc, -p));
    return t_c + amplitude * std::pow(rc, -p);
}

double extrapolated_tip(const RefinedTips& t) {
    return extrapolated_tip(t.tip[1], t.tip[2], t.tip[3], 2);
}

}  // namespace

TEST_CASE("calculix: checkerboards of contrast 3 and 10 within 5% of the converged continuum") {
    if (skip_without_ccx()) return;
    const MixedScene& s = scene("checkerboard");
    for (const RefinedTips& t : kCheckerboardTips) {
        CAPTURE(t.contrast);
        CAPTURE(t.nu);
        CHECK(calculix_tip(s, t.contrast, t.nu) == doctest::Approx(t.tip[0]).epsilon(1e-4));
        const double reference = extrapolated_tip(t);
        const double ours = engine_tip(s, t.contrast, t.nu);
        MESSAGE("checkerboard, contrast "
                << t.contrast << ", nu " << t.nu << ": tip " << ours << " m, CalculiX extrapolated "
                << reference << " m (4 elements per voxel " << t.tip[3] << " m), error "
                << 100.0 * (ours / reference - 1.0) << " %");
        CHECK(std::fabs(ours / reference - 1.0) < 0.05);
    }
}

// Random mixtures and soft slices (issue 40). References: CalculiX at 1, 2 and 3 elements per
// voxel (C3D20R, stored; regenerate with BHM_SCENE=random50 BHM_CONTRAST=10 BHM_NU=0.49
// BHM_REFINE=3 and the probe above), extrapolated as the checkerboards'; the one-element tip is
// solved live and must equal the stored one. Each reference's own uncertainty is printed: its
// distance from the finest mesh. The slices (soft/stiff voxel layers across the beam) are the
// fitting half of mixed_link_stiffening's three constants (engine/internal/link_confinement.hpp);
// the random mixtures are held out, as are the layered, cored, heated and checkerboard bodies
// above. mixed_link_bending_factor (the bending and shear of a mixed link beside stiffer links)
// has no constant to fit and leaves the slices and checkerboards bit-identical; every random
// mixture is held out for it too. Targets: up to 10x within 5 % of the extrapolated tip, 30x
// within 10 %.
// Not here: random50 at 30x and nu 0.35, whose three meshes are not monotone (no reference), and
// 30x at nu 0, whose references are uncertain by 5-12 % (order 0.3: edge contacts, as the
// checkerboard's).
namespace {

enum class Half { Fitting, HeldOut };

struct MixtureTips {
    const char* scene;
    double contrast, nu;
    Half half;
    bool in_ctest;  // the rest on demand: -tc="calculix table: random*" --no-skip
    double tip[3];  // m, 1 to 3 elements per voxel
};

constexpr MixtureTips kMixtureTips[] = {
    {"slices", 3, 0.49, Half::Fitting, false, {-0.00056435, -0.000572674, -0.000574434}},
    {"slices", 10, 0.35, Half::Fitting, false, {-0.00160034, -0.00162021, -0.00162428}},
    {"slices", 10, 0.49, Half::Fitting, true, {-0.00121704, -0.00125144, -0.00125896}},
    {"slices", 30, 0.35, Half::Fitting, false, {-0.00429125, -0.00436025, -0.00437564}},
    {"slices", 30, 0.49, Half::Fitting, false, {-0.00290364, -0.00302524, -0.00305422}},
    {"random30", 3, 0, Half::HeldOut, false, {-0.000736509, -0.00073833, -0.000738685}},
    {"random30", 3, 0.35, Half::HeldOut, false, {-0.000720033, -0.000724738, -0.000725848}},
    {"random30", 3, 0.49, Half::HeldOut, false, {-0.000672847, -0.000683613, -0.000686218}},
    {"random30", 10, 0, Half::HeldOut, false, {-0.00191152, -0.0019291, -0.00193469}},
    {"random30", 10, 0.35, Half::HeldOut, false, {-0.00181912, -0.00184642, -0.00185514}},
    {"random30", 10, 0.49, Half::HeldOut, true, {-0.00157689, -0.00163752, -0.00165251}},
    {"random30", 30, 0.35, Half::HeldOut, false, {-0.00450508, -0.00461146, -0.00465698}},
    {"random30", 30, 0.49, Half::HeldOut, true, {-0.00357854, -0.00383815, -0.00390619}},
    {"random50", 3, 0, Half::HeldOut, false, {-0.000625476, -0.000627614, -0.000628102}},
    {"random50", 3, 0.35, Half::HeldOut, false, {-0.000615477, -0.000619172, -0.000620215}},
    {"random50", 3, 0.49, Half::HeldOut, true, {-0.000576498, -0.00058559, -0.00058811}},
    {"random50", 10, 0, Half::HeldOut, true, {-0.00132254, -0.00134564, -0.00135363}},
    {"random50", 10, 0.35, Half::HeldOut, true, {-0.00128197, -0.00130345, -0.00131249}},
    {"random50", 10, 0.49, Half::HeldOut, true, {-0.00111745, -0.00115959, -0.00117351}},
    {"random50", 30, 0.49, Half::HeldOut, false, {-0.00204432, -0.00217568, -0.00223042}},
    // The blind check (scene random50b above; BHM_SCENE=random50b BHM_REFINE=3, 1.6 min).
    {"random50b", 10, 0, Half::HeldOut, true, {-0.00122948, -0.00124487, -0.00124995}},
};

struct MixtureOutcome {
    double error = 0.0, tolerance = 0.0;
};

MixtureOutcome compare_mixture(const MixtureTips& t) {
    const MixedScene& s = scene(t.scene);
    CHECK(calculix_tip(s, t.contrast, t.nu) == doctest::Approx(t.tip[0]).epsilon(1e-4));
    const double reference = extrapolated_tip(t.tip[0], t.tip[1], t.tip[2], 1);
    REQUIRE(std::isfinite(reference));
    const double ours = engine_tip(s, t.contrast, t.nu);
    const MixtureOutcome o{ours / reference - 1.0, t.contrast <= 10.0 ? 0.05 : 0.10};
    const std::string label =
        std::string(t.scene) + (t.half == Half::Fitting ? " (fitting)" : " (held out)");
    MESSAGE(label << ", contrast " << t.contrast << ", nu " << t.nu << ": tip " << ours
                  << " m, CalculiX extrapolated " << reference << " m (+-"
                  << 100.0 * std::fabs(t.tip[2] / reference - 1.0) << " %), error "
                  << 100.0 * o.error << " %");
    return o;
}

}  // namespace

TEST_CASE("calculix: random mixtures within 5% (10x) and 10% (30x) of the converged continuum") {
    if (skip_without_ccx()) return;
    for (const MixtureTips& t : kMixtureTips) {
        if (!t.in_ctest) continue;
        CAPTURE(t.scene);
        CAPTURE(t.contrast);
        CAPTURE(t.nu);
        const MixtureOutcome o = compare_mixture(t);
        CHECK(std::fabs(o.error) < o.tolerance);
    }
}

//   build/bin/test_engine -tc="calculix table: random*" --no-skip -s
TEST_CASE("calculix table: random mixtures and slices, every stored case" * doctest::skip()) {
    if (skip_without_ccx()) return;
    for (const MixtureTips& t : kMixtureTips) {
        CAPTURE(t.scene);
        const MixtureOutcome o = compare_mixture(t);
        CHECK(std::fabs(o.error) < o.tolerance);
    }
}

// The whole table of docs/physics.md (every scene, contrast 10 and 100, nu 0, 0.35, 0.49):
// minutes on the 2-core machine, so run on demand:
//   build/bin/test_engine -tc="calculix table*" --no-skip -s
TEST_CASE("calculix table: bodies of two materials, every scene" * doctest::skip()) {
    if (skip_without_ccx()) return;
    for (const MixedScene& s : mixed_scenes())
        for (double contrast : {10.0, 100.0})
            for (double nu : {0.0, 0.35, 0.49})
                compare(s, contrast, nu);
}

// One scene on demand: BHM_SCENE=checkerboard BHM_CONTRAST=100 BHM_NU=0.49
//   build/bin/test_engine -tc="calculix probe*" --no-skip -s
TEST_CASE("calculix probe: one scene of two materials" * doctest::skip()) {
    if (skip_without_ccx()) return;
    const char* name = std::getenv("BHM_SCENE");
    const char* contrast = std::getenv("BHM_CONTRAST");
    const char* nu = std::getenv("BHM_NU");
    REQUIRE(name);
    const double k = contrast ? std::atof(contrast) : 10.0, n = nu ? std::atof(nu) : 0.35;
    // BHM_REFINE=R: CalculiX alone, meshes of 1 to R elements per voxel (3 if R < 1), each tip
    // printed as it comes (R = 5 on the 12x4x4 checkerboard: minutes and a few GB); with
    // BHM_GRADING=q the elements shrink toward every voxel face (ccx::Mesh::grading), which
    // resolves a checkerboard's singular edges far better at the same count.
    if (const char* refine = std::getenv("BHM_REFINE")) {
        const int most = std::atoi(refine) >= 1 ? std::atoi(refine) : 3;
        for (int r = 1; r <= most; ++r) {
            std::printf("%s, contrast %g, nu %g, %d elements per voxel: CalculiX tip %.6g m\n",
                        name, k, n, r, calculix_tip(scene(name), k, n, r));
            std::fflush(stdout);
        }
        return;
    }
    compare(scene(name), k, n);
}

// The strain profile through the thickness at mid-span, engine / CalculiX (2 elements per voxel,
// so the voxel centres are nodes): per voxel layer z the x and y strains between neighbouring
// centres and the z strain to the next layer, averaged over y (docs/physics.md quotes it). On
// demand, BHM_NY (the strip's width) and BHM_X0 (the section, default mid-span) optional:
//   BHM_SCENE=bilayer-soft-active BHM_CONTRAST=10 BHM_NU=0.49
//     build/bin/test_engine -tc="calculix profile*" --no-skip -s
TEST_CASE("calculix profile: strains through the thickness at mid-span" * doctest::skip()) {
    if (skip_without_ccx()) return;
    const char* name = std::getenv("BHM_SCENE");
    REQUIRE(name);
    MixedScene sc = scene(name);
    if (const char* ny = std::getenv("BHM_NY")) sc.ny = std::atoi(ny);
    const char* contrast = std::getenv("BHM_CONTRAST");
    const char* nu_text = std::getenv("BHM_NU");
    const double k = contrast ? std::atof(contrast) : 10.0,
                 nu = nu_text ? std::atof(nu_text) : 0.35;
    const int x0 = std::getenv("BHM_X0") ? std::atoi(std::getenv("BHM_X0")) : sc.nx / 2;
    World w(Model::build(engine_body(sc, k, nu)));
    settle(w, sc.nx - 1);
    const Model& m = w.model();
    auto pos = [&](int x, int y, int z) { return w.voxel_position_m(voxel_at(m, x, y, z)); };
    auto dist = [&](std::array<double, 3> a, std::array<double, 3> b) {
        return std::sqrt((a[0] - b[0]) * (a[0] - b[0]) + (a[1] - b[1]) * (a[1] - b[1]) +
                         (a[2] - b[2]) * (a[2] - b[2]));
    };
    // CalculiX at 2 elements per voxel: the voxel centres are nodes.
    const int r = 2;
    const ccx::Mesh mesh = calculix_mesh(sc, r);
    const auto u = calculix_solve(
        sc, k, nu, r, mesh, ccx::nodes_where(mesh, [](double, double, double) { return true; }));
    auto cu = [&](double x, double y, double z) {  // the displacement of the node at a point
        auto index = [&](double p, int axis) {
            return static_cast<int>(std::lround(p / (mesh.size[axis] / (2.0 * mesh.n[axis]))));
        };
        return u.at(mesh.node_id(index(x, 0), index(y, 1), index(z, 2)));
    };
    for (int z = 0; z < sc.nz; ++z) {
        double ex = 0, ey = 0, ez = 0, cx = 0, cy = 0, cz = 0;
        for (int y = 0; y < sc.ny; ++y) {
            ex += dist(pos(x0 + 1, y, z), pos(x0, y, z)) / kL - 1.0;
            cx += (cu((x0 + 1) * kL, (y + 0.5) * kL, (z + 0.5) * kL)[0] -
                   cu(x0 * kL, (y + 0.5) * kL, (z + 0.5) * kL)[0]) /
                  kL;
            if (z + 1 < sc.nz) {
                ez += dist(pos(x0, y, z + 1), pos(x0, y, z)) / kL - 1.0;
                cz += (cu(x0 * kL, (y + 0.5) * kL, (z + 1.5) * kL)[2] -
                       cu(x0 * kL, (y + 0.5) * kL, (z + 0.5) * kL)[2]) /
                      kL;
            }
            if (y + 1 < sc.ny) {
                ey += dist(pos(x0, y + 1, z), pos(x0, y, z)) / kL - 1.0;
                cy += (cu(x0 * kL, (y + 1.5) * kL, (z + 0.5) * kL)[1] -
                       cu(x0 * kL, (y + 0.5) * kL, (z + 0.5) * kL)[1]) /
                      kL;
            }
        }
        const double n = sc.ny, n1 = std::max(1, sc.ny - 1);
        char line[256];
        std::snprintf(
            line, sizeof line,
            "z %d (mat %d): e_x %+.4e / %+.4e   e_y %+.4e / %+.4e   e_z(z,z+1) %+.4e / %+.4e", z,
            sc.stiff(x0, 0, z), ex / n, cx / n, ey / n1, cy / n1, ez / n, cz / n);
        MESSAGE(line);
    }
}

// The engine alone against the stored references (no CalculiX run): every stored mixture, slice
// and checkerboard row, or those of BHM_SCENE / BHM_CONTRAST / BHM_NU where set. Seconds:
//   build/bin/test_engine -tc="calculix stored: *" --no-skip -s
TEST_CASE("calculix stored: the engine against every stored reference" * doctest::skip()) {
    const char* name = std::getenv("BHM_SCENE");
    const char* contrast = std::getenv("BHM_CONTRAST");
    const char* nu = std::getenv("BHM_NU");
    auto wanted = [&](const char* scene_name, double k, double n) {
        return (!name || std::string(name) == scene_name) &&
               (!contrast || std::fabs(std::atof(contrast) - k) < 1e-9) &&
               (!nu || std::fabs(std::atof(nu) - n) < 1e-9);
    };
    double sum2 = 0.0;
    int rows = 0;
    auto report = [&](const char* scene_name, double k, double n, double ours, double reference,
                      const char* half) {
        const double error = ours / reference - 1.0;
        sum2 += error * error;
        ++rows;
        std::printf("%-12s %-8s k %4g nu %4g: tip %.6g m, reference %.6g m, error %+.2f %%\n",
                    scene_name, half, k, n, ours, reference, 100.0 * error);
        std::fflush(stdout);
    };
    for (const RefinedTips& t : kCheckerboardTips)
        if (wanted("checkerboard", t.contrast, t.nu))
            report("checkerboard", t.contrast, t.nu,
                   engine_tip(scene("checkerboard"), t.contrast, t.nu), extrapolated_tip(t),
                   "fitting");
    for (const MixtureTips& t : kMixtureTips)
        if (wanted(t.scene, t.contrast, t.nu))
            report(t.scene, t.contrast, t.nu, engine_tip(scene(t.scene), t.contrast, t.nu),
                   extrapolated_tip(t.tip[0], t.tip[1], t.tip[2], 1),
                   t.half == Half::Fitting ? "fitting" : "held-out");
    if (rows > 0) std::printf("rms over %d rows: %.2f %%\n", rows, 100.0 * std::sqrt(sum2 / rows));
}
