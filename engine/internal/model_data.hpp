#pragma once
// Private to the engine: the immutable, precomputed data of a Model (structure of arrays).
//
// Layout: the cost of a step follows the body, not its workspace.
// - Voxels are compacted into dense arrays in lattice order of the occupied cells (x fastest): the
//   public voxel index v is the array index. The arrays are padded to a multiple of kLanes with
//   inert dummy voxels (no mass, never moved, no links) so every loop runs whole SIMD vectors, and
//   one more dummy sits past them (the +x neighbour the last slot reads).
// - Links are owned by their - end: link slot v of axis a joins voxel v to its +a neighbour
//   plus[a][v] (slot present when link_exists[a][v] is 1). Because voxels are in lattice order,
//   the +x neighbour of v is always v + 1 when it exists, so the x link pass is fully contiguous;
//   the +y and +z neighbours are gathered through plus[1] / plus[2]. Absent slots are computed
//   like real ones with zero stiffness and a straight chord, so their outputs are exactly zero.
// - The voxel pass gathers, per voxel and axis, the link it owns (slot v, contiguous) and the link
//   whose + end it is: slot v - 1 for x (contiguous; zero when that slot holds no link to v) and
//   minus[a][v] for y, z (kNoLink, a slot that is always zero, when there is none). The summation
//   order is fixed (per axis: the - link, then the + link), so results are deterministic, no
//   atomics are needed, and a step allocates nothing.
// - Solid regions need no gathers: the slots are cut into runs of whole vectors. In a "uniform"
//   run every link's + end is the slot plus one constant (y: the voxels of a row, z: of a layer)
//   and every voxel's - link is its slot minus one constant, so the passes read both ends
//   contiguously; the other runs go through the tables. A short uniform run between gathered
//   ones is gathered too (a loop entry costs more than a few gathered vectors), and a chunk with
//   no - link on an axis (the first row or layer) takes the next chunk's offset. Absent links may
//   point anywhere (their chord is replaced), so they never break a run; zero slots before slot 0
//   (link_lead) and dummy voxels after the last slot (up to `stored`) keep every offset read in
//   bounds.
// - Positions are stored relative to the body's origin (the low corner of the occupied cells'
//   bounding box, `origin_m`), and the floor is at -origin_z: a body gives the same trajectory
//   bit for bit wherever it sits in its workspace (shifted by whole voxels); the World adds the
//   origin back where it reports positions.
#include <array>
#include <cstdint>
#include <vector>

#include "engine/body_spec.hpp"
#include "engine/internal/muscle_drive.hpp"
#include "engine/model.hpp"

namespace bhm::engine {

//! Voxel arrays are padded to a multiple of this (8 doubles = one AVX-512 vector; the float link
//! pass runs 16 lanes and an 8-lane tail).
inline constexpr int kLanes = 8;
//! Link scratch arrays hold at least this many always-zero slots before slot 0 (the x gather of
//! voxel 0 reads slot -1; absent y/z links point at kNoLink).
inline constexpr int kLinkLead = kLanes;
inline constexpr int kNoLink = -1;

//! Link slots [begin, end) of one axis; delta > 0: the + end of slot c is voxel c + delta,
//! delta == 0: it is plus[axis][c].
struct LinkRun {
    int begin = 0, end = 0, delta = 0;
};

//! Voxel slots [begin, end); below_y > 0: the y link whose + end is voxel c sits in slot
//! c - below_y (a zero slot when there is none), and the same for z; 0: through minus[].
struct VoxelRun {
    int begin = 0, end = 0, below_y = 0, below_z = 0;
};

//! J = kSquareTorsionFactor L^4 of a square section (Saint-Venant).
inline constexpr double kSquareTorsionFactor = 0.1406;
//! The stiffness of a link's symmetric bending mode (shear, ta = tb), 6 G I / L = G L^3 / 2, over
//! its torsion stiffness G J / L: the kernel takes it from k_torsion (link_pass.cpp).
inline constexpr float kShearPerTorsion = static_cast<float>(0.5 / kSquareTorsionFactor);

//! Per link slot constants of one lattice axis (float: they feed the float link kernel).
struct LinkParams {
    std::vector<float> exists;      //!< (slots) 1 = a real link, 0 = no link at this slot
    std::vector<float> k_axial;     //!< E A / L (N/m)
    std::vector<float> k_bend;      //!< E I / L (N m/rad): the curvature mode's stiffness
    std::vector<float> k_torsion;   //!< G J / L (N m/rad)
    std::vector<float> damp_steps;  //!< Rayleigh beta / dt: damping term = k * beta * rate
    //! Rayleigh beta (s) of the implicit bond damping (damping_pass.hpp); all zero, and damp_steps
    //! used instead, when it is explicit
    std::vector<float> damp_beta;
    //! Implicit bond damping: the relaxation factor 1 / (1 + dt max(P_a, P_b)) of the link's
    //! damping rates per sweep, P the sum over a voxel's links of a bound on each link's damping
    //! rate (damping_pass.hpp); 0 when it is explicit
    std::vector<float> damp_relax;
    std::vector<float> rest_base;  //!< rest length with no actuation (m)
    std::vector<float> rest_sin;   //!< d(rest)/d sin(2 pi f tau) (m)
    std::vector<float> rest_cos;   //!< d(rest)/d cos(2 pi f tau) (m)
};

//! Poisson coupling (engine/internal/poisson.hpp): per voxel slot and per link slot, float like the
//! link kernel. Absent (all empty) when no voxel couples its axes (every nu = 0, or a 1-D body).
//! Side index s: 0 = the voxel's - half-link on an axis, 1 = its + half-link.
struct PoissonParams {
    bool active = false;
    std::array<std::vector<float>, 3> has_plus;   //!< voxel: 1 = a link to its +a neighbour
    std::array<std::vector<float>, 3> has_minus;  //!< voxel: 1 = a link to its -a neighbour
    std::vector<float> shear;                     //!< voxel: G (Pa)
    std::vector<float> lambda1;                   //!< cross modulus, octant with 1 linked axis
    std::vector<float> lambda2;                   //!< cross modulus, octant with 2 linked axes
    std::vector<float> lambda3;                   //!< cross modulus, octant with 3 linked axes
    //! voxel, per octant o = 4 sx + 2 sy + sz: lambda_o / 8 of that octant (its linked axes
    //! picked from lambda1..3), precomputed so the kernel does not rebuild it every step
    std::array<std::vector<float>, 8> octant_lambda8;
    //! voxel, per [axis][side]: the centre strain the volumetric term of that side's octants uses,
    //! mu = own * e_side + other * e_other_side + far * e_far + pair * d (poisson.hpp).
    //! The strains are stresses over the voxel's E (a link's strain times E_link / E_voxel), so
    //! two materials in one link stay springs in series. Inside a column of a `mixed` body mu
    //! also takes the other side's mu_pair * d.
    std::array<std::array<std::vector<float>, 2>, 3> mu_own, mu_other, mu_far, mu_pair;
    //! voxel, per [axis][side]: gamma = dev_scale * e_side + mu_pair * d (twice that inside a
    //! column of a mixed body, where mu_pair is half the half-link's weight), or mu at a column's
    //! end (where mu_far < 0); dev_scale > 0 exactly where that half-link exists
    std::array<std::array<std::vector<float>, 2>, 3> dev_scale;
    //! voxel, per [axis][side]: the link slot e_far reads (the partner's other link), or kNoLink
    std::array<std::array<std::vector<std::int32_t>, 2>, 3> far_slot;
    //! voxel, per [axis][side]: where the far link carries a relaxed split d, the end estimate
    //! reads that link's half at the partner, e_far = e + far_pair * d (poisson.cpp); else 0
    std::array<std::array<std::vector<float>, 2>, 3> far_pair;
    std::array<std::vector<float>, 3> rest_scale;  //!< link slot: -L / M_link, 0 if absent
    std::array<std::vector<float>, 3> pair_step;   //!< link slot: relaxation step of d, 0 if none
    //! link slot: x E of a link of one material whose d is held by the penalty x E d^2 / 2 per
    //! volume (poisson.hpp), 0 for a mixed or isolated link and where there is no d
    std::array<std::vector<float>, 3> pair_penalty;
    //! link slot: 1 - pair_step * pair_penalty, the share of d a relaxation step keeps before
    //! the gradient of the octants' energy (1 where there is no penalty)
    std::array<std::vector<float>, 3> pair_keep;
    //! voxels at either end of a link with a relaxed d (isolated or mixed)
    std::vector<std::int32_t> pair_voxels;
    bool mixed = false;  //!< some link joins two materials and carries a relaxed split d
    //! The far links of the column-end estimates, as sparse lists (a few voxels per column), so
    //! the dense loops read them contiguously instead of through tables on every slot:
    //! far_reads[a]: (voxel, side, slot) with mu_far != 0, copies strain[slot] (+ pair d) to the
    //! voxel's far strain (y and z; x too in a mixed body, otherwise x reads v - 2 and v + 1
    //! directly); far_pair_reads[a]: those with a d, whose far gradient also moves that d;
    //! far_pos_links[a] / far_neg_links[a]:
    //! (link slot, voxel) whose far gradient (far_pos / far_neg) that link's stress takes.
    struct FarRead {
        std::int32_t voxel = 0, side = 0, slot = 0;
        float pair = 0.0f;  //!< far_pair of (voxel, side): e_far = strain + pair * d of the slot
    };
    struct FarLink {
        std::int32_t link = 0, voxel = 0;
    };
    std::array<std::vector<FarRead>, 3> far_reads, far_pair_reads;
    std::array<std::vector<FarLink>, 3> far_pos_links, far_neg_links;
};

struct Model::Data {
    BodySpec spec;
    double voxel_size_m = 0.0;
    double rotary_inertia_scale = 1.0;  //!< BodySpec::rotary_inertia_scale
    double dt_s = 0.0;
    double stable_dt_s = 0.0;  //!< the largest stable step (before dt_fraction)
    double total_mass_kg = 0.0;
    int link_count = 0;

    int voxels = 0;  //!< n, real voxels
    int slots = 0;   //!< n rounded up to kLanes: the length every pass loops over
    int stored = 0;  //!< length of per-voxel arrays: slots + the largest uniform link offset
    int link_lead = kLinkLead;                //!< zero slots before slot 0 in link scratch arrays
    std::array<int, 3> origin_cell{0, 0, 0};  //!< low corner of the voxels' bounding box
    std::array<double, 3> origin_m{0, 0, 0};  //!< origin_cell * L: added to reported positions

    // Voxel list (lattice order) and the map back.
    std::vector<int> voxel_cell;                       //!< (n) lattice cell of voxel v
    std::vector<std::uint8_t> voxel_material;          //!< (n) 1-based material index
    std::vector<std::uint8_t> voxel_fixed;             //!< (n) 1 = all six DOF held
    std::vector<int> cell_voxel;                       //!< (cells) voxel index or -1
    std::vector<std::array<double, 3>> rest_position;  //!< (stored) relative to origin_m

    // Neighbour tables (stored). plus[a][v]: the +a neighbour of v (v itself when none; only
    // read for y and z). minus[a][v]: the link slot whose + end is v, or kNoLink (y and z).
    std::array<std::vector<std::int32_t>, 3> plus;
    std::array<std::vector<std::int32_t>, 3> minus;
    std::array<std::vector<LinkRun>, 3> link_runs;  //!< in order, per axis; slots of vectors
                                                    //!< without a link are in none
    std::vector<VoxelRun> voxel_runs;               //!< cover [0, slots) in order

    // Per voxel constants (stored), double: they feed the double voxel pass.
    std::vector<double> movable;         //!< 1 = integrated (a voxel and not fixed)
    std::vector<double> mass;            //!< kg (0 for dummies)
    std::vector<double> dt_inv_mass;     //!< dt / m (0 for dummies or fixed)
    std::vector<double> dt_inv_inertia;  //!< dt / I, I = s m L^2 / 6
    std::vector<double> linear_keep;     //!< 1 / (1 + dt c_g / m): implicit global damping
    //! Per axis: 1 / (1 + dt c_g,rot / I) where the voxel turns about that world axis, 0 where
    //! it may not (a held voxel's locked axes, model.cpp "Held voxels' rotation")
    std::array<std::vector<double>, 3> angular_keep;
    //! A held voxel that turns (model.cpp, "Held voxels' rotation"): its rotational spring to
    //! the clamp, kClampWallStiffness E L^3 (N m/rad); 0 for every other voxel
    std::vector<double> wall_stiffness;
    std::vector<double> floor_k;  //!< floor penalty stiffness (N/m), E L
    std::vector<double> floor_c;  //!< floor collision damping (N s/m)
    std::vector<double> mu_static;
    std::vector<double> mu_dynamic;
    std::vector<double>
        act_sin;  //!< size scale = 1 + act_sin * sin(2 pi f tau) + act_cos * cos(..)
    std::vector<double> act_cos;
    bool any_active = false;
    int implicit_sweeps = 0;  //!< 0: explicit bond damping; n: n Jacobi sweeps (damping_pass.hpp)

    std::array<LinkParams, 3> links;  //!< per axis, one slot per voxel slot
    PoissonParams poisson;
    //! Muscle voxels (muscle_drive.hpp): their signals and per-axis strains; signals == 0 in a
    //! body driven by the sine model
    MuscleDrive muscle;

    //! Springs across shared voxel edges (edge_springs.hpp), structure of arrays over the
    //! springs (empty in most bodies). Float like the link kernel (the float edge kernel reads
    //! them); vectors in a's body frame.
    struct EdgeSprings {
        std::vector<std::int32_t> a, b;          //!< voxel slots, b = a + one step along two axes
        std::array<std::vector<float>, 3> half;  //!< a's centre to the edge's midpoint (m)
        std::array<std::vector<float>, 3> edge;  //!< unit, along the edge
        std::vector<float> k_across, k_along;    //!< per point (N/m)
        std::vector<float> damping;              //!< per point, c / dt (N/m): on the gap's change
        //! a's and b's size scale 1 + act_sin sin + act_cos cos, copied from the voxels so the
        //! kernel reads them in spring order
        std::vector<float> act_sin_a, act_cos_a, act_sin_b, act_cos_b;
        //! dt / I of a and b (0 for a voxel that does not turn), set with the step
        std::vector<float> turn_a, turn_b;
        float gauss_m = 0.0f;  //!< the edge's midpoint to a Gauss point, L / (2 sqrt 3)
        //! The scatter's plan (edge_pass): the voxels in some spring (ascending), and for voxel
        //! touched[t] its springs' increments at end * size() + n for the entries
        //! [incidence_begin[t], incidence_begin[t + 1]) of incidence, in spring order
        std::vector<std::int32_t> touched, incidence_begin, incidence;
        int size() const { return static_cast<int>(a.size()); }
    };
    EdgeSprings edge_springs;
};

}  // namespace bhm::engine
