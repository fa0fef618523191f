#pragma once
// The verdict of one verification: judged on the verify measure that corresponds to the
// experiment's fitness measure (centre-of-mass fitness on the centre of mass, a bend angle on the
// bend angle), every other measure reported beside it, and no measure deciding where the FEM's
// value is under its floor (a 1.4 degree bend angle differing by 59 % says nothing about a body
// whose centre of mass agrees within 4 %). docs/verify.md, "The verdict".
#include <array>
#include <optional>
#include <string>
#include <vector>

#include "evo/experiment/experiment.hpp"

namespace bhm::evo {

struct LoadComparison;

enum class VerifyMeasure { Com, ComYz, Tip, Bend, Rms };
inline constexpr std::array<VerifyMeasure, 5> kVerifyMeasures = {
    VerifyMeasure::Com, VerifyMeasure::ComYz, VerifyMeasure::Tip, VerifyMeasure::Bend,
    VerifyMeasure::Rms};
//! report.json's key of each measure (as in each load's relative_difference).
const char* verify_measure_key(VerifyMeasure m);
//! How a verdict line names it: "the centre of mass", "the tip", ...
const char* verify_measure_label(VerifyMeasure m);

//! The verify measure that corresponds to an experiment's fitness measure.
VerifyMeasure verify_measure_of(FitnessMeasure fitness);

//! Below these the FEM's value of a measure is reported but never decides the verdict.
struct MeasureFloors {
    double bend_deg = 3.0;                //!< a bend angle under 3 degrees
    double displacement_fraction = 0.02;  //!< under 2 % of the largest voxel displacement
};

//! One measure over every load: its largest relative difference where the FEM's value clears the
//! floor (`judged`), and over every load where it could be divided at all (`any`).
struct MeasureSummary {
    VerifyMeasure measure = VerifyMeasure::Com;
    std::optional<double> judged, any;
    double fem_largest = 0.0;  //!< the FEM's largest value over the loads (m, or degrees)
};

struct VerdictDecision {
    std::optional<VerifyMeasure> decided_by;  //!< none when every measure is under its floor
    double worst = 0.0;                       //!< the deciding measure's largest difference
    bool agrees = false;
    std::vector<MeasureSummary> measures;  //!< the experiment's first, then kVerifyMeasures' order
};

//! A relative difference as a verdict prints it: 0.2271 -> "22.7 %".
std::string percent(double v);

//! The FEM's value of a measure at one load (m, or degrees for the bend angle).
double fem_magnitude(const LoadComparison& c, VerifyMeasure m);
//! Whether that value clears its floor (at least the floor; the largest displacement is the
//! FEM's largest voxel displacement at that load).
bool above_floor(const LoadComparison& c, VerifyMeasure m, const MeasureFloors& floors);

//! Judges on `experiment`'s measure where it clears its floor at some load; else on the first of
//! kVerifyMeasures that does.
VerdictDecision decide_verdict(const std::vector<LoadComparison>& loads, VerifyMeasure experiment,
                               double tolerance, const MeasureFloors& floors = {});

//! "agrees within 4.2 % (tolerance 10 %) on the centre of mass" and, when the experiment's measure
//! was under its floor, why another decided.
std::string verdict_line(const VerdictDecision& d, VerifyMeasure experiment, double tolerance,
                         const MeasureFloors& floors = {});

//! The other measures, one phrase each: "the tip 17.0 %, the bend angle 59.0 % (under its
//! 3 deg floor: not judged)".
std::string measures_beside(const VerdictDecision& d, const MeasureFloors& floors = {});

}  // namespace bhm::evo
