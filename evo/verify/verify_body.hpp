#pragma once
// One body checked against the continuum: the reach check, the CalculiX solve at rest, +A and -A
// (fem_model, ccx_deck, ccx_run), our engine's quasi-static answer at the same loads
// (quasi_static), and their comparison: tip displacement, bend angle, YZ displacement of the
// centre of mass and the per-voxel displacement RMS, each as a relative difference.
#include <array>
#include <optional>
#include <string>
#include <vector>

#include "engine/body_spec.hpp"
#include "evo/experiment/experiment.hpp"
#include "evo/verify/ccx_run.hpp"
#include "evo/verify/fem_model.hpp"
#include "evo/verify/quasi_static.hpp"
#include "evo/verify/verify_progress.hpp"

namespace bhm::evo {

struct VerifyOptions {
    FemMeshOptions mesh;  // C3D8I, 2 per voxel edge: 0.3 % of a mesh 8x finer (docs/verify.md)
    bool nlgeom = false;  //!< geometrically nonlinear steps (slow: off by default, docs/verify.md)
    double tolerance = 0.10;    //!< largest relative difference that still "agrees"
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
    std::optional<double> tip, bend, com_yz, rms;
    double worst() const;  //!< the largest present, 0 when none
};

struct LoadComparison {
    std::string load;  //!< "rest", "+A", "-A"
    double temperature_c = 0.0;
    ResponseMeasures fem, engine;
    Differences differences;
    double fem_rms_m = 0.0;  //!< RMS of the FEM's voxel displacements
    //! Both deformed shapes as voxel poses in the FemModel's voxel order and our engine's frame
    //! (fem_shape.hpp): what the studio draws, ours solid and the FEM's as a ghost over it.
    engine::VoxelPoses fem_shape, engine_shape;
};

enum class VerifyStatus { Compared, OutOfReach };

struct BodyVerification {
    VerifyStatus status = VerifyStatus::Compared;
    std::string reason;  //!< why the body is out of reach
    int voxels = 0, held_voxels = 0, active_voxels = 0;
    int tip_cell = -1;
    std::vector<LoadComparison> loads;
    double worst = 0.0;  //!< the largest relative difference over every load and measure
    bool agrees = false;
    double tolerance = 0.10;
    //! The experiment's fitness measure, evaluated quasi-statically on both answers (the
    //! largest over +A and -A): what ranks bodies in a run's top K.
    double fem_score = 0.0, engine_score = 0.0;
    double fem_cpu_s = 0.0, fem_wall_s = 0.0, engine_cpu_s = 0.0;
    int fem_nodes = 0, fem_elements = 0;
    FemModel fem_model;
    std::vector<NodalDisplacements> fem_displacements;  //!< per load
    //! "agrees within X %", "differs by Y %" or "outside the continuum's reach: why".
    std::string verdict() const;
};

//! Why a body cannot be compared (no held voxel, voxels not attached to a held one), or "".
std::string continuum_reach_problem(const engine::BodySpec& spec);

//! Checks one body (the engine input of a framed body, make_body_spec). Throws
//! std::runtime_error with one line: body too large, ccx missing, a failed solve, an engine that
//! diverged or did not settle; VerifyCancelled when options.control's flag is raised (the ccx
//! child is killed, its temporary folder removed).
BodyVerification verify_body(const engine::BodySpec& spec, FitnessMeasure measure,
                             const VerifyOptions& options);

}  // namespace bhm::evo
