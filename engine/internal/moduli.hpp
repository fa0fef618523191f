#pragma once
// Private to the engine: the moduli a material's stiffness is built from, shared by the model, the
// limits and the edge springs.
#include "engine/body_spec.hpp"

namespace bhm::engine {

//! Two materials joined end to end (the two halves of a link, the two voxels of an edge spring)
//! act as springs in series, each over half the length: 2 a b / (a + b).
inline double series(double a, double b) {
    return 2.0 * a * b / (a + b);
}

//! G = E / (2 (1 + nu)).
inline double shear_modulus(const Material& m) {
    return m.youngs_modulus_pa / (2.0 * (1.0 + m.poisson_ratio));
}

}  // namespace bhm::engine
