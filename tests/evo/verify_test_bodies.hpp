#pragma once
// Bodies the continuum-check tests share (bhm verify's geometry choice, the coarse mesh's
// nonlinear part).
#include <cstddef>

#include "engine/body_spec.hpp"

namespace bhm::test {

//! An nx x ny x nz bar (E 5 MPa, voxel 1 cm): its z = 0 layer active (cte 0.01 /degC), held at its
//! x = 0 layer, actuated by +-amplitude_c.
inline engine::BodySpec verify_bilayer(double amplitude_c, int nx = 10, int nz = 2, int ny = 2) {
    engine::BodySpec s;
    s.nx = nx;
    s.ny = ny;
    s.nz = nz;
    s.voxel_size_m = 0.01;
    engine::Material passive;
    passive.youngs_modulus_pa = 5e6;
    engine::Material active = passive;
    active.cte_per_c = 0.01;
    s.materials = {passive, active};
    s.material.assign(static_cast<std::size_t>(s.cell_count()), 1);
    s.fixed.assign(static_cast<std::size_t>(s.cell_count()), 0);
    for (int z = 0; z < s.nz; ++z)
        for (int y = 0; y < s.ny; ++y)
            for (int x = 0; x < s.nx; ++x) {
                const auto c = static_cast<std::size_t>(s.cell_index(x, y, z));
                if (z == 0) s.material[c] = 2;
                if (x == 0) s.fixed[c] = 1;
            }
    s.damping.global_ratio = 0.01;
    s.actuation.temperature_amplitude_c = amplitude_c;
    return s;
}

}  // namespace bhm::test
