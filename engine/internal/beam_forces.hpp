#pragma once
// Private to the engine: the beam equations of one link (link_pass.cpp), shared by the elastic
// link pass and the implicit bond damping's pass (damping_pass.cpp), which evaluates them at the
// deformation rate times beta (C = beta K).
//
// Inputs in world coordinates: the chord direction e, 1 / |d|, the axial deformation x and the
// end rotations ta (- end) and tb (+ end) relative to the link frame; stiffnesses at the current
// size (ka = E A / L, kb = E I / L, kt = G J / L). Outputs: the force on the + end (the - end gets
// its opposite) and both end moments.
#include "engine/internal/link_kinematics.hpp"
#include "engine/internal/model_data.hpp"

namespace bhm::engine {

struct BeamLoads {
    float f0, f1, f2;     //!< on the + end
    float ma0, ma1, ma2;  //!< moment on the - end
    float mb0, mb1, mb2;  //!< moment on the + end
};

BHM_ENGINE_INLINE BeamLoads beam_loads(float ex, float ey, float ez, float inv_len, float axial,
                                       float kb, float kt, float ta0, float ta1, float ta2,
                                       float tb0, float tb1, float tb2) {
    // Absent links have zero stiffness, so everything below is exactly zero for them.
    // Bending as its two modes: the antisymmetric one (curvature, ta = -tb) with E I / L,
    // the symmetric one (shear, ta = tb) with 3 (2 G / E) E I / L = G L^3 / 2, taken from the
    // torsion stiffness G J / L (kShearPerTorsion), so the lattice's shear modulus is G
    // (E / 2 with Euler-Bernoulli beams alone, at any nu). At nu = 0 both are the beam's
    // M_a = -k_b (4 ta + 2 tb), M_b = -k_b (2 ta + 4 tb).
    // (At most the Euler-Bernoulli 3 k_b: auxetic voxels, G > E / 2, keep the beam's shear,
    // so the stable step, which knows 4 E I / L, still bounds this mode.)
    const float ks_g = kShearPerTorsion * kt, ks_beam = 3.0f * kb;
    const float ks = ks_g < ks_beam ? ks_g : ks_beam;  // (std::fmin would not vectorise)
    const float twist_a = ta0 * ex + ta1 * ey + ta2 * ez;
    const float twist_b = tb0 * ex + tb1 * ey + tb2 * ez;
    const float kt_twist = kt * (twist_b - twist_a);
    // Bending acts on the normal parts only: add back the e components, then torsion.
    const float sym_e = ks * (twist_a + twist_b), anti_e = kb * (twist_a - twist_b);
    const float along_a = kt_twist + sym_e + anti_e;
    const float along_b = -kt_twist + sym_e - anti_e;
    const float sym0 = ks * (ta0 + tb0), anti0 = kb * (ta0 - tb0);
    const float sym1 = ks * (ta1 + tb1), anti1 = kb * (ta1 - tb1);
    const float sym2 = ks * (ta2 + tb2), anti2 = kb * (ta2 - tb2);
    BeamLoads o;
    o.ma0 = -(sym0 + anti0) + along_a * ex;
    o.ma1 = -(sym1 + anti1) + along_a * ey;
    o.ma2 = -(sym2 + anti2) + along_a * ez;
    o.mb0 = -(sym0 - anti0) + along_b * ex;
    o.mb1 = -(sym1 - anti1) + along_b * ey;
    o.mb2 = -(sym2 - anti2) + along_b * ez;
    const float s0 = o.ma0 + o.mb0, s1 = o.ma1 + o.mb1, s2 = o.ma2 + o.mb2;
    o.f0 = -axial * ex + (ey * s2 - ez * s1) * inv_len;
    o.f1 = -axial * ey + (ez * s0 - ex * s2) * inv_len;
    o.f2 = -axial * ez + (ex * s1 - ey * s0) * inv_len;
    return o;
}

}  // namespace bhm::engine
