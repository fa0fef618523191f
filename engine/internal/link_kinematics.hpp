#pragma once
// Private to the engine: the co-rotational frame of one link and the end rotations relative to it.
//
// Coordinates: x runs along the link's lattice axis, y and z are the next two axes in cyclic order
// (a proper rotation, so quaternion vector parts permute the same way). Inputs: d = centre of the
// + end minus centre of the - end, and both orientations (body to world).
//
// The link frame (Hiller & Lipson 2014 express bond forces in a frame that turns with the bond):
//   1. mean orientation M = normalise(qa + qb) (qb sign-aligned with qa); it carries the link's
//      rest axis to a = M x;
//   2. swing S: the shortest rotation taking a to the chord direction e = d / |d|;
//   3. link frame F = S M: its x axis lies on the chord, its roll is the two ends' mean roll.
// Each end's rotation relative to F is small even when the beam as a whole turns by 90 degrees or
// more, so linear beam theory holds per link (large rotations, small strains). Everything stays in
// world coordinates: the relative rotation of an end, q conj(F), is directly a world-frame
// rotation, and since M is the exact midpoint of qa and qb, qb conj(M) = conj(qa conj(M)).
#include <cmath>

// The link pass is one loop the compiler must see whole to vectorise: force inlining.
#define BHM_ENGINE_INLINE inline __attribute__((always_inline))

namespace bhm::engine {

struct LinkFrame {
    float length;        //!< |d|
    float ex, ey, ez;    //!< chord direction e = d / |d|
    float axis_cos;      //!< a . e: 1 for a straight link; <= 0 means sheared past 90 deg
    float theta_neg[3];  //!< rotation vector of the - end relative to F, world frame (rad)
    float theta_pos[3];  //!< same for the + end
};

//! Smallest 1 + a.e the swing is computed for: past it the link is reported as diverged by the
//! caller; the clamp only keeps the numbers finite.
inline constexpr float kMinOnePlusCos = 0.5f;

//! The frame of chord d whose length len = sqrt(d.d) is already known (computed exactly so).
BHM_ENGINE_INLINE LinkFrame link_frame(float dx, float dy, float dz, float len, float aw, float ax,
                                       float ay, float az, float bw, float bx, float by, float bz) {
    LinkFrame f;
    const float inv_len = 1.0f / len;
    f.length = len;
    f.ex = dx * inv_len;
    f.ey = dy * inv_len;
    f.ez = dz * inv_len;
    // q and -q are the same rotation: align b with a before averaging.
    const float sign = std::copysign(1.0f, aw * bw + ax * bx + ay * by + az * bz);
    float mw = aw + sign * bw, mx = ax + sign * bx, my = ay + sign * by, mz = az + sign * bz;
    const float inv_norm = 1.0f / std::sqrt(mw * mw + mx * mx + my * my + mz * mz);
    mw *= inv_norm;
    mx *= inv_norm;
    my *= inv_norm;
    mz *= inv_norm;
    // a = M x (first column of M's rotation matrix).
    const float a0 = 1.0f - 2.0f * (my * my + mz * mz);
    const float a1 = 2.0f * (mx * my + mw * mz);
    const float a2 = 2.0f * (mx * mz - mw * my);
    // Swing S = (1 + a.e, a x e) / sqrt(2 (1 + a.e)): the shortest arc from a to e.
    const float cos_ae = a0 * f.ex + a1 * f.ey + a2 * f.ez;
    f.axis_cos = cos_ae;
    const float one_plus_raw = 1.0f + cos_ae;
    const float one_plus = 0.5f * (one_plus_raw + kMinOnePlusCos +
                                   std::fabs(one_plus_raw - kMinOnePlusCos));  // max, branch-free
    const float inv_n = 1.0f / std::sqrt(2.0f * one_plus);
    const float sw = one_plus * inv_n;
    const float sx = (a1 * f.ez - a2 * f.ey) * inv_n;
    const float sy = (a2 * f.ex - a0 * f.ez) * inv_n;
    const float sz = (a0 * f.ey - a1 * f.ex) * inv_n;
    // g = qa conj(M): the - end's rotation relative to M, world frame; the + end's is conj(g).
    const float gw = aw * mw + ax * mx + ay * my + az * mz;
    const float gx = -aw * mx + ax * mw - (ay * mz - az * my);
    const float gy = -aw * my + ay * mw - (az * mx - ax * mz);
    const float gz = -aw * mz + az * mw - (ax * my - ay * mx);
    // Relative to F: t = g conj(S) (- end), conj(g) conj(S) (+ end); rotation vector ~ 2 vec(t).
    // p conj(S) = (pw sw + pv.sv, -pw sv + sw pv - pv x sv)
    const float gs = gx * sx + gy * sy + gz * sz;
    const float cx = gy * sz - gz * sy, cy = gz * sx - gx * sz, cz = gx * sy - gy * sx;
    const float two_neg = std::copysign(2.0f, gw * sw + gs);
    f.theta_neg[0] = two_neg * (-gw * sx + sw * gx - cx);
    f.theta_neg[1] = two_neg * (-gw * sy + sw * gy - cy);
    f.theta_neg[2] = two_neg * (-gw * sz + sw * gz - cz);
    // For conj(g) = (gw, -gv): the cross product flips sign with gv.
    const float two_pos = std::copysign(2.0f, gw * sw - gs);
    f.theta_pos[0] = two_pos * (-gw * sx - sw * gx + cx);
    f.theta_pos[1] = two_pos * (-gw * sy - sw * gy + cy);
    f.theta_pos[2] = two_pos * (-gw * sz - sw * gz + cz);
    return f;
}

BHM_ENGINE_INLINE float chord_length(float dx, float dy, float dz) {
    return std::sqrt(dx * dx + dy * dy + dz * dz);
}

struct Chord {
    float d0, d1, d2;  //!< + end minus - end, link axis first
};

//! The chord of the link from voxel a to voxel b, from positions p0, p1, p2 in the link's axis
//! order; an absent link (exists 0) sees the straight rest chord, so its (discarded) numbers stay
//! finite whatever its neighbours do. The link pass and the Poisson strain pass both measure it
//! so, and must agree bit for bit.
BHM_ENGINE_INLINE Chord link_chord(const double* __restrict p0, const double* __restrict p1,
                                   const double* __restrict p2, int a, int b, float exists,
                                   float rest_base) {
    return {static_cast<float>(p0[b] - p0[a]) * exists + (1.0f - exists) * rest_base,
            static_cast<float>(p1[b] - p1[a]) * exists, static_cast<float>(p2[b] - p2[a]) * exists};
}

BHM_ENGINE_INLINE LinkFrame link_frame(float dx, float dy, float dz, float aw, float ax, float ay,
                                       float az, float bw, float bx, float by, float bz) {
    return link_frame(dx, dy, dz, chord_length(dx, dy, dz), aw, ax, ay, az, bw, bx, by, bz);
}

}  // namespace bhm::engine
