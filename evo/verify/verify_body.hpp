#pragma once
// One body checked against the continuum: the reach check, the CalculiX solve at rest, +A and -A
// (a muscle body: rest and peak activation; fem_model, ccx_deck, ccx_run), our engine's
// quasi-static answer at the same loads (quasi_static), and their comparison: tip displacement,
// bend angle, displacement of the centre of mass (3-D and YZ) and the per-voxel displacement RMS,
// each as a relative difference, judged on the experiment's own measure (verdict.hpp).
#include <array>
#include <optional>
#include <string>
#include <vector>

#include "engine/body_spec.hpp"
#include "evo/experiment/experiment.hpp"
#include "evo/verify/ccx_deck.hpp"
#include "evo/verify/ccx_run.hpp"
#include "evo/verify/fem_mesh_choice.hpp"
#include "evo/verify/fem_model.hpp"
#include "evo/verify/quasi_static.hpp"
#include "evo/verify/verdict.hpp"
#include "evo/verify/verify_progress.hpp"

namespace bhm::evo {

//! Whether the FEM's steps are geometrically nonlinear: chosen from our engine's answer
//! (Automatic), or forced (`--linear`, `--nlgeom`).
enum class FemGeometry { Automatic, Linear, Nonlinear };

struct VerifyOptions {
    //! None: the automatic mesh, refined where the body is narrow (fem_mesh_choice.hpp); set, the
    //! caller's (`--element`, `--subdivision`).
    std::optional<FemMeshOptions> mesh;
    FemGeometry geometry = FemGeometry::Automatic;
    //! Automatic: nonlinear when our engine turns a voxel, or bends the root-to-tip line, by more
    //! than this at some load (docs/verify.md, "Linear or nonlinear").
    double nlgeom_above_deg = 10.0;
    //! ... or when the actuation's free strain (cte A, or a muscle's contraction) exceeds this:
    //! a linear step cannot tell +A from -A, and at the paper's 14.5 % the engine's and the
    //! continuum's answers are not antisymmetric (docs/verify.md, "Two continuum laws").
    double nlgeom_above_strain = 0.05;
    //! Nonlinear steps solved on a mesh of one element per voxel and their nonlinear part added
    //! to this mesh's linear answer (coarse_nonlinearity.hpp): what the evolution loop's checks
    //! do, several times quicker; bhm verify solves in full.
    bool nonlinear_from_coarse_mesh = false;
    //! ... while our engine turns no voxel and bends no more than this; beyond, the correction
    //! drifts (docs/verify.md, "Linear or nonlinear") and the steps are solved in full.
    double coarse_nonlinearity_below_deg = 30.0;
    //! Nonlinear steps: the second continuum law solved only where the first law's answer does
    //! not agree alone (the verdict is the nearer law's, and the nearer of two cannot turn an
    //! agreement into a difference; what is lost is the other law's figure and the laws' spread):
    //! the evolution loop's checks; bhm verify solves both.
    bool second_law_only_where_first_differs = false;
    //! ... and the law solved first on the coarse mesh (where the steps are solved in full on the
    //! mesh, Saint Venant-Kirchhoff is, and is first): the loop's, Neo-Hookean, the law our
    //! engine has been nearer wherever both were solved (docs/verify.md, "Two continuum laws").
    FemMaterialLaw first_law = FemMaterialLaw::Hooke;
    //! The coarse mesh's nonlinear solves with full integration (C3D20) from the start where the
    //! mesh is C3D20R for a section 1 voxel across (fem_mesh_choice.hpp): there one C3D20R across
    //! a section has spurious modes, its nonlinear solve failed on 3 of 7 such bodies measured,
    //! and a failed attempt cost 5-55 s (a check is 4-27 s); where C3D20R converges C3D20 costs
    //! up to 1.9x, a loss that the failures outweigh (docs/verify.md, "loop40d"). Off, C3D20R
    //! first and C3D20 only after it fails (bhm verify --coarse-reduced-first).
    bool coarse_full_integration_where_narrow = true;
    double tolerance = 0.10;    //!< largest relative difference that still "agrees"
    MeasureFloors floors;       //!< under these a measure is reported, never judged
    int max_voxels = 4000;      //!< larger bodies are refused (time and memory of the solve)
    int threads = 1;            //!< solver threads of ccx
    QuasiStaticOptions engine;
    std::string keep_dir;       //!< where ccx works and leaves its files; "" = a temporary folder
    VerifyControl control;      //!< progress reports and a cancel flag (the studio's worker)
};

//! The measures of one answer at one load.
struct ResponseMeasures {
    std::array<double, 3> tip_m{};   //!< displacement of the tip voxel's centre
    double bend_deg = 0.0;           //!< rotation of the root-to-tip line
    std::array<double, 2> com_yz_m{};  //!< YZ displacement of the centre of mass
    std::array<double, 3> com_m{};   //!< displacement of the centre of mass
};

//! Relative differences (ours against the FEM); absent where the FEM's value is too small to
//! divide by (a measure of a load that hardly moves the body).
struct Differences {
    std::optional<double> tip, bend, com_yz, com, rms;
    double worst() const;  //!< the largest present, 0 when none
    std::optional<double> of(VerifyMeasure m) const;
};

struct LoadComparison {
    std::string load;            //!< "rest", "+A", "-A"; a muscle body's "rest", "peak"
    double temperature_c = 0.0;  //!< a muscle body's: the activation (0, 1)
    ResponseMeasures fem, engine;
    Differences differences;
    double fem_rms_m = 0.0;  //!< RMS of the FEM's voxel displacements
    double fem_largest_m = 0.0;  //!< the FEM's largest voxel displacement (the floors' scale)
    //! Both deformed shapes as voxel poses in the FemModel's voxel order and our engine's frame
    //! (fem_shape.hpp): what the studio draws, ours solid and the FEM's as a ghost over it.
    engine::VoxelPoses fem_shape, engine_shape;
};

enum class VerifyStatus { Compared, OutOfReach };

//! One CalculiX solve of a verification and its cost: what a check's time is made of (the
//! evolution loop's overhead, docs/verify.md "Overhead, measured"). Timings only: never part of
//! a run's state.
struct FemSolveCost {
    bool coarse = false;  //!< on the coarse mesh (one element per voxel edge), else the mesh's own
    bool nlgeom = false;
    std::string law;  //!< the continuum law of a nonlinear solve, "" for a linear one
    std::string element;  //!< as written in the deck: "C3D20R", "C3D20" (full integration), "C3D8I"
    int elements = 0, nodes = 0;
    double deck_s = 0.0;  //!< building the input deck's text (wall)
    double cpu_s = 0.0, wall_s = 0.0;
};

//! What a muscle body's verdict adds: which loads it was judged at, and why no -A.
inline constexpr const char* kMuscleLoadsNote =
    " at rest and peak activation (a muscle only contracts: no -A)";

struct BodyVerification {
    VerifyStatus status = VerifyStatus::Compared;
    std::string reason;  //!< why the body is out of reach
    int voxels = 0, held_voxels = 0, active_voxels = 0;
    //! Driven by the muscle model: the loads are rest and peak activation (ccx_deck.hpp).
    bool muscle = false;
    int tip_cell = -1;
    std::vector<LoadComparison> loads;
    //! The verdict: the experiment's measure (`measure`) decides where it clears its floor, else
    //! the first measure that does (`decision.decided_by`); `worst` is the deciding measure's
    //! largest relative difference over the loads, `worst_any` the largest of every measure.
    VerifyMeasure measure = VerifyMeasure::Com;
    VerdictDecision decision;
    double worst = 0.0, worst_any = 0.0;
    bool agrees = false;
    double tolerance = 0.10;
    MeasureFloors floors;
    //! The experiment's fitness measure, evaluated quasi-statically on both answers (the
    //! largest over +A and -A): what ranks bodies in a run's top K.
    double fem_score = 0.0, engine_score = 0.0;
    double fem_cpu_s = 0.0, fem_wall_s = 0.0, engine_cpu_s = 0.0;
    std::vector<FemSolveCost> fem_solves;  //!< each successful ccx solve, in order
    int fem_nodes = 0, fem_elements = 0;
    FemMeshChoice mesh;           //!< the mesh solved, and why (automatic or the caller's)
    bool nlgeom = false;          //!< the FEM's steps were geometrically nonlinear
    //! ... their nonlinear part from the coarse mesh (VerifyOptions::nonlinear_from_coarse_mesh)
    bool nlgeom_from_coarse_mesh = false;
    std::string geometry_reason;  //!< why: "--linear", or our engine's largest rotation
    //! Nonlinear steps only: the continuum law the verdict was judged against, the nearer of two
    //! (ccx_deck.hpp, FemMaterialLaw), the other one and its verdict value (none where it has no
    //! verdict or its solve failed), and how far the two laws' own answers differ on the
    //! verdict's measure (the reference's uncertainty from its unknown large-strain law).
    std::string material_law, other_law;
    std::optional<double> other_law_worst, law_spread;
    //! The other law was not solved, as the first one's answer agrees alone
    //! (VerifyOptions::second_law_only_where_first_differs).
    bool other_law_skipped = false;
    double engine_rotation_deg = 0.0;  //!< our engine's largest voxel rotation over the loads
    double engine_bend_deg = 0.0;      //!< ... and largest bend angle
    FemModel fem_model;
    std::vector<NodalDisplacements> fem_displacements;  //!< per load
    //! "agrees within X % (tolerance T %) on MEASURE", "differs by Y % (...) on MEASURE" or
    //! "outside the continuum's reach: why".
    std::string verdict() const;
    //! Every other measure's largest difference, one phrase each (verdict.hpp).
    std::string beside() const;
    //! Nonlinear steps: "judged against the Neo-Hookean continuum, the nearer of two laws
    //! (Saint Venant-Kirchhoff: 22.7 %); the two laws' answers differ by 14 % on ..."; else "".
    std::string laws() const;
};

//! The largest free strain of the body's active voxels at the actuation's extremes (|cte A|, or
//! a muscle's largest scale - 1); 0 without active voxels.
double actuation_free_strain(const engine::BodySpec& spec);

//! Why a body cannot be compared (no held voxel, voxels not attached to a held one), or "".
std::string continuum_reach_problem(const engine::BodySpec& spec);

//! The FEM's answer alone on `mesh` (no engine run, no comparison): each load's `fem`,
//! `fem_rms_m` and `fem_largest_m`, in verify_body's load order, steps nonlinear when `nlgeom`.
//! What the mesh-error estimate compares, reusing the first verification's engine answer.
struct FemAnswer {
    std::vector<LoadComparison> loads;
    double cpu_s = 0.0, wall_s = 0.0;
    int nodes = 0;
};
FemAnswer solve_fem(const engine::BodySpec& spec, const FemMeshOptions& mesh, bool nlgeom,
                    const VerifyOptions& options);

//! Checks one body (the engine input of a framed body, make_body_spec). Throws
//! std::runtime_error with one line: body too large, ccx missing, a failed solve, an engine that
//! diverged or did not settle; VerifyCancelled when options.control's flag is raised (the ccx
//! child is killed, its temporary folder removed).
BodyVerification verify_body(const engine::BodySpec& spec, FitnessMeasure measure,
                             const VerifyOptions& options);

}  // namespace bhm::evo
