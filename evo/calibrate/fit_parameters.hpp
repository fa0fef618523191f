#pragma once
// The simulation parameters bhm calibrate can fit (--fit), each as a factor on the experiment's
// value (searched in log space) or, for the phase lag, an added angle. The sine model's drive
// (cte, amplitude, frequency, phase_lag) and the muscle model's twitch (rise_s, decay_s,
// contraction_strain, engine/muscle.hpp) each apply only to an experiment whose materials use
// that model: parse_fit_list refuses the other with the field that says why.
#include <string>
#include <vector>

#include "evo/experiment/experiment.hpp"

namespace bhm::evo {

enum class FitKind {
    YoungsModulus,  //!< E of one material, or of every material by one factor
    Density,        //!< rho, likewise
    Cte,            //!< the active materials' expansion coefficient
    Amplitude,      //!< actuation.temperature_amplitude_c
    Frequency,      //!< actuation.frequency_hz
    PhaseLag,       //!< added to every voxel's actuation phase (radians)
    BondDamping,    //!< simulation.bond_damping_ratio
    GlobalDamping,  //!< simulation.global_damping_ratio
    Friction,       //!< static and dynamic friction of every material, by one factor
    MuscleRise,     //!< muscle.rise_s of one muscle material, or of every one by one factor
    MuscleDecay,    //!< muscle.decay_s, likewise
    MuscleStrain,   //!< muscle.contraction_strain, likewise
};

struct FitParameter {
    std::string name;  //!< as given to --fit ("E", "E:muscle", "bond_damping", ...)
    FitKind kind = FitKind::YoungsModulus;
    int material = -1;      //!< 0-based material index, -1 = every material it applies to
    bool log_scale = true;  //!< x = ln(factor); false: x = added radians (phase lag)
    //! Bounds on x: ln(1/5)..ln(5), narrowed where the field's own range is nearer (a muscle's
    //! time constants and contraction strain, engine/muscle.hpp).
    double lower = 0.0, upper = 0.0;
};

//! Parses a comma-separated --fit list against the experiment. Throws std::runtime_error with a
//! one-line reason (unknown name, unknown material, repeated name, a parameter that is zero in the
//! experiment so no factor can move it, a parameter of the other actuation model than the
//! experiment's materials use).
std::vector<FitParameter> parse_fit_list(const std::string& list, const Experiment& experiment);

//! The names --fit accepts, for --help.
std::string fit_names_help();

//! The experiment with x applied (x[i] for parameters[i]). The phase lag is added to the
//! experiment's actuation.phase_offset_rad (wrapped into [-pi, pi]); phase_lag_rad keeps the
//! lag fitted, for the report.
struct FitPoint {
    Experiment experiment;
    double phase_lag_rad = 0.0;
};
FitPoint apply_fit(const Experiment& base, const std::vector<FitParameter>& parameters,
                   const std::vector<double>& x);

//! Copies the values of the fitted parameters from `calibrated` (apply_fit's experiment) into
//! `target`, leaving everything else of target as it is: the studio applies a calibration made
//! on the body shown to the document being edited. Throws std::runtime_error when the two have
//! different material lists (a factor on "every material" would not mean the same materials).
void copy_fitted_values(const Experiment& calibrated, const std::vector<FitParameter>& parameters,
                        Experiment& target);

//! The physical value of parameter p at x (the first material's where it spans several) and
//! its unit.
double fit_value(const Experiment& base, const FitParameter& p, double x);
const char* fit_unit(const FitParameter& p);

}  // namespace bhm::evo
