#pragma once
// Private to the engine: the immutable, precomputed data of a Model (structure of arrays).
//
// Layout. Voxels live on their lattice grid: every per-cell array has one slot per lattice cell
// (empty cells hold an inert dummy) plus `pad` trailing slots, so the link between cell c and its
// +axis neighbour is always (c, c + stride[axis]): links are index pairs with an implicit, constant
// offset, which makes both passes of a step contiguous and vectorisable (no gathers, no atomics).
// Link slot c of axis a exists when both cells are occupied (link_exists[a][c] == 1).
#include <array>
#include <cstdint>
#include <vector>

#include "engine/body_spec.hpp"
#include "engine/model.hpp"

namespace bhm::engine {

//! Per link slot constants of one lattice axis (float: they feed the float link kernel).
struct LinkParams {
    std::vector<float> exists;      //!< 1 = a real link, 0 = no link at this slot
    std::vector<float> k_axial;     //!< E A / L (N/m)
    std::vector<float> k_bend;      //!< E I / L (N m/rad); moments use 4x and 2x this
    std::vector<float> k_torsion;   //!< G J / L (N m/rad)
    std::vector<float> damp_steps;  //!< Rayleigh beta / dt: damping term = k * beta * rate
    std::vector<float> rest_base;   //!< rest length with no actuation (m)
    std::vector<float> rest_sin;    //!< d(rest)/d sin(2 pi f tau) (m)
    std::vector<float> rest_cos;    //!< d(rest)/d cos(2 pi f tau) (m)
};

struct Model::Data {
    BodySpec spec;
    double voxel_size_m = 0.0;
    double dt_s = 0.0;
    double stable_dt_s = 0.0;  //!< the largest stable step (before dt_fraction)
    double total_mass_kg = 0.0;
    int link_count = 0;

    // Grid geometry.
    int cells = 0;                       //!< nx * ny * nz
    int pad = 0;                         //!< nx * ny: trailing padding of per-cell arrays
    std::array<int, 3> stride{1, 1, 1};  //!< cell offset of the +x, +y, +z neighbour

    // Compact voxel list (lattice order) and the map back.
    std::vector<int> voxel_cell;               //!< (n) lattice cell of voxel v
    std::vector<std::uint8_t> voxel_material;  //!< (n) 1-based material index
    std::vector<std::uint8_t> voxel_fixed;     //!< (n) 1 = all six DOF held
    std::vector<int> cell_voxel;               //!< (cells) voxel index or -1

    // Per cell constants (cells + pad), double: they feed the double voxel pass.
    std::vector<double> occupied;        //!< 1 = a voxel, 0 = empty dummy
    std::vector<double> movable;         //!< 1 = integrated (occupied and not fixed)
    std::vector<double> mass;            //!< kg (0 for empty cells)
    std::vector<double> dt_inv_mass;     //!< dt / m (0 for empty or fixed)
    std::vector<double> dt_inv_inertia;  //!< dt / I, I = m L^2 / 6
    std::vector<double> linear_keep;     //!< 1 / (1 + dt c_g / m): implicit global damping
    std::vector<double> angular_keep;    //!< 1 / (1 + dt c_g,rot / I)
    std::vector<double> floor_k;         //!< floor penalty stiffness (N/m), E L
    std::vector<double> floor_c;         //!< floor collision damping (N s/m)
    std::vector<double> mu_static;
    std::vector<double> mu_dynamic;
    std::vector<double>
        act_sin;  //!< size scale = 1 + act_sin * sin(2 pi f tau) + act_cos * cos(..)
    std::vector<double> act_cos;
    bool any_active = false;

    std::array<LinkParams, 3> links;  //!< per axis, slots [0, cells)
};

}  // namespace bhm::engine
