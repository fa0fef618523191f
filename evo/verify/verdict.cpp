#include "evo/verify/verdict.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>

#include "evo/verify/verify_body.hpp"

namespace bhm::evo {

const char* verify_measure_key(VerifyMeasure m) {
    switch (m) {
        case VerifyMeasure::Com: return "com_displacement";
        case VerifyMeasure::ComYz: return "com_yz_displacement";
        case VerifyMeasure::Tip: return "tip_displacement";
        case VerifyMeasure::Bend: return "bend_angle";
        case VerifyMeasure::Rms: return "voxel_displacement_rms";
    }
    return "";
}

const char* verify_measure_label(VerifyMeasure m) {
    switch (m) {
        case VerifyMeasure::Com: return "the centre of mass";
        case VerifyMeasure::ComYz: return "the centre of mass's YZ displacement";
        case VerifyMeasure::Tip: return "the tip";
        case VerifyMeasure::Bend: return "the bend angle";
        case VerifyMeasure::Rms: return "the voxel displacement RMS";
    }
    return "";
}

VerifyMeasure verify_measure_of(FitnessMeasure fitness) {
    switch (fitness) {
        case FitnessMeasure::ComFinal3d:
        case FitnessMeasure::ComMax3d: return VerifyMeasure::Com;
        case FitnessMeasure::ComFinalYz:
        case FitnessMeasure::ComMaxYz: return VerifyMeasure::ComYz;
        case FitnessMeasure::BendAngleDeg: return VerifyMeasure::Bend;
    }
    return VerifyMeasure::Com;
}

double fem_magnitude(const LoadComparison& c, VerifyMeasure m) {
    const auto& f = c.fem;
    switch (m) {
        case VerifyMeasure::Com: return std::hypot(f.com_m[0], f.com_m[1], f.com_m[2]);
        case VerifyMeasure::ComYz: return std::hypot(f.com_yz_m[0], f.com_yz_m[1]);
        case VerifyMeasure::Tip: return std::hypot(f.tip_m[0], f.tip_m[1], f.tip_m[2]);
        case VerifyMeasure::Bend: return f.bend_deg;
        case VerifyMeasure::Rms: return c.fem_rms_m;
    }
    return 0.0;
}

bool above_floor(const LoadComparison& c, VerifyMeasure m, const MeasureFloors& floors) {
    const double value = fem_magnitude(c, m);
    if (m == VerifyMeasure::Bend) return value >= floors.bend_deg;
    return value > 0.0 && value >= floors.displacement_fraction * c.fem_largest_m;
}

std::string percent(double v) {
    char text[32];
    std::snprintf(text, sizeof text, "%.1f %%", 100.0 * v);
    return text;
}

namespace {

MeasureSummary summarise(const std::vector<LoadComparison>& loads, VerifyMeasure m,
                         const MeasureFloors& floors) {
    MeasureSummary s;
    s.measure = m;
    auto raise = [](std::optional<double>& to, double v) { to = std::max(to.value_or(v), v); };
    for (const auto& c : loads) {
        s.fem_largest = std::max(s.fem_largest, fem_magnitude(c, m));
        const auto d = c.differences.of(m);
        if (!d) continue;
        raise(s.any, *d);
        if (above_floor(c, m, floors)) raise(s.judged, *d);
    }
    return s;
}

std::string floor_text(VerifyMeasure m, const MeasureFloors& floors) {
    char text[96];
    if (m == VerifyMeasure::Bend)
        std::snprintf(text, sizeof text, "its %g deg floor", floors.bend_deg);
    else
        std::snprintf(text, sizeof text, "its floor of %g %% of the largest displacement",
                      100.0 * floors.displacement_fraction);
    return text;
}

std::string largest_text(const MeasureSummary& s) {
    char text[48];
    if (s.measure == VerifyMeasure::Bend)
        std::snprintf(text, sizeof text, "%.2g deg", s.fem_largest);
    else
        std::snprintf(text, sizeof text, "%.3g mm", 1e3 * s.fem_largest);
    return text;
}

}  // namespace

VerdictDecision decide_verdict(const std::vector<LoadComparison>& loads, VerifyMeasure experiment,
                               double tolerance, const MeasureFloors& floors) {
    VerdictDecision d;
    d.measures.push_back(summarise(loads, experiment, floors));
    for (VerifyMeasure m : kVerifyMeasures)
        if (m != experiment) d.measures.push_back(summarise(loads, m, floors));
    for (const auto& s : d.measures)
        if (s.judged) {
            d.decided_by = s.measure;
            d.worst = *s.judged;
            break;
        }
    d.agrees = d.decided_by && d.worst <= tolerance;
    return d;
}

std::string verdict_line(const VerdictDecision& d, VerifyMeasure experiment, double tolerance,
                         const MeasureFloors& floors) {
    char tol[32];
    std::snprintf(tol, sizeof tol, "%g %%", 100.0 * tolerance);
    if (!d.decided_by)
        return std::string("not judged: every measure is under its floor (the body hardly moves; "
                           "tolerance ") +
               tol + ")";
    std::string line = (d.agrees ? "agrees within " : "differs by ") + percent(d.worst) +
                       " (tolerance " + tol + ") on " + verify_measure_label(*d.decided_by);
    if (*d.decided_by != experiment) {
        const MeasureSummary& own = d.measures.front();
        line += std::string(" (the experiment's measure, ") + verify_measure_label(experiment) +
                ", at most " + largest_text(own) + ", is under " + floor_text(experiment, floors) +
                ")";
    }
    return line;
}

std::string measures_beside(const VerdictDecision& d, const MeasureFloors& floors) {
    std::string out;
    for (const auto& s : d.measures) {
        if (d.decided_by && s.measure == *d.decided_by) continue;
        if (!out.empty()) out += ", ";
        out += verify_measure_label(s.measure);
        if (!s.any) {
            out += " n/a (too small to divide by)";
            continue;
        }
        out += " " + percent(*s.any);
        if (!s.judged)
            out += " (" + largest_text(s) + ", under " + floor_text(s.measure, floors) +
                   ": not judged)";
    }
    return out;
}

}  // namespace bhm::evo
