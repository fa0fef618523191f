#pragma once
// The verification suite's CalculiX (ccx) decks: a structured C3D20R brick mesh of a box, written
// as a .inp and solved by the project's one ccx driver (evo/verify/ccx_run.hpp, which bhm verify
// uses too). CalculiX is an independent 3-D continuum FEM (Debian calculix-ccx).
#include <algorithm>
#include <array>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <functional>
#include <map>
#include <sstream>
#include <stdexcept>
#include <string>
#include <vector>

#include "evo/verify/ccx_run.hpp"

namespace bhm::engine::test::ccx {

inline bool available() {
    return evo::ccx_available();
}

struct Material {
    double e = 5e6, nu = 0.35, rho = 1000.0, cte = 0.0;
};

//! A box [0, size] meshed with n[i] C3D20R elements per axis; `material_of(ex, ey, ez)` picks the
//! material index of each element.
struct Mesh {
    std::array<double, 3> size{};
    std::array<int, 3> n{};
    // Node id of refined-grid point (i, j, k), 0 <= i <= 2 n[0] (half-element spacing).
    int node_id(int i, int j, int k) const {
        return 1 + i + (2 * n[0] + 1) * (j + (2 * n[1] + 1) * k);
    }
    //! Grading toward the voxel faces: 0 = uniform; q > 1 maps each voxel's local
    //! coordinate t in [0, 1] by 0.5 (2 t)^q below 0.5 and its mirror above, so elements shrink
    //! toward every voxel face and edge. voxel: the voxel size; offset: where voxel faces lie
    //! along each axis modulo the voxel size.
    double grading = 0.0;
    double voxel = 0.0;
    std::array<double, 3> offset{};
    //! Where set, the element corners along that axis (n[axis] + 1 coordinates, ascending),
    //! in place of the uniform (or graded) spacing: a mesh refined unevenly along one axis.
    std::array<std::vector<double>, 3> corners{};
    double corner(int axis, int i) const {
        if (!corners[axis].empty()) return corners[axis][static_cast<std::size_t>(i / 2)];
        const double u = size[axis] * i / (2.0 * n[axis]);
        if (grading <= 0.0) return u;
        const double shifted = u - offset[axis];
        const double cell = std::floor(shifted / voxel + 1e-9);
        const double t = std::clamp(shifted / voxel - cell, 0.0, 1.0);
        const double g = t < 0.5 ? 0.5 * std::pow(2.0 * t, grading)
                                 : 1.0 - 0.5 * std::pow(2.0 * (1.0 - t), grading);
        return offset[axis] + (cell + g) * voxel;
    }
    double coordinate(int axis, int i) const {
        if ((grading <= 0.0 && corners[axis].empty()) || i % 2 == 0) return corner(axis, i);
        return 0.5 * (corner(axis, i - 1) + corner(axis, i + 1));
    }
    std::array<double, 3> position(int i, int j, int k) const {
        return {coordinate(0, i), coordinate(1, j), coordinate(2, k)};
    }
    // C3D20 has corner nodes (all even) and edge midpoints (exactly one index odd).
    static bool used(int i, int j, int k) { return (i % 2) + (j % 2) + (k % 2) <= 1; }
};

//! Node ids of every node where pick(x, y, z) is true.
inline std::vector<int> nodes_where(const Mesh& m,
                                    const std::function<bool(double, double, double)>& pick) {
    std::vector<int> out;
    for (int k = 0; k <= 2 * m.n[2]; ++k)
        for (int j = 0; j <= 2 * m.n[1]; ++j)
            for (int i = 0; i <= 2 * m.n[0]; ++i) {
                if (!Mesh::used(i, j, k)) continue;
                const auto p = m.position(i, j, k);
                if (pick(p[0], p[1], p[2])) out.push_back(m.node_id(i, j, k));
            }
    return out;
}

inline void write_set(std::ostream& out, const char* kind, const std::string& name,
                      const std::vector<int>& ids) {
    out << "*" << kind << ", " << kind << "=" << name << "\n";
    for (std::size_t i = 0; i < ids.size(); ++i)
        out << ids[i] << ((i % 10 == 9 || i + 1 == ids.size()) ? ",\n" : ", ");
}

//! Writes the mesh, materials and element sets (ELSET M1, M2, ...; NALL; EALL).
inline void write_mesh(std::ostream& out, const Mesh& m, const std::vector<Material>& materials,
                       const std::function<int(int, int, int)>& material_of) {
    out << "*NODE, NSET=NALL\n";
    char line[160];
    for (int k = 0; k <= 2 * m.n[2]; ++k)
        for (int j = 0; j <= 2 * m.n[1]; ++j)
            for (int i = 0; i <= 2 * m.n[0]; ++i) {
                if (!Mesh::used(i, j, k)) continue;
                const auto p = m.position(i, j, k);
                std::snprintf(line, sizeof line, "%d, %.10g, %.10g, %.10g\n", m.node_id(i, j, k),
                              p[0], p[1], p[2]);
                out << line;
            }
    // Abaqus node order of a 20-node brick, as refined-grid offsets from its low corner.
    static const int kOffsets[20][3] = {{0, 0, 0}, {2, 0, 0}, {2, 2, 0}, {0, 2, 0}, {0, 0, 2},
                                        {2, 0, 2}, {2, 2, 2}, {0, 2, 2}, {1, 0, 0}, {2, 1, 0},
                                        {1, 2, 0}, {0, 1, 0}, {1, 0, 2}, {2, 1, 2}, {1, 2, 2},
                                        {0, 1, 2}, {0, 0, 1}, {2, 0, 1}, {2, 2, 1}, {0, 2, 1}};
    std::map<int, std::vector<int>> by_material;
    out << "*ELEMENT, TYPE=C3D20R, ELSET=EALL\n";
    int id = 0;
    for (int ez = 0; ez < m.n[2]; ++ez)
        for (int ey = 0; ey < m.n[1]; ++ey)
            for (int ex = 0; ex < m.n[0]; ++ex) {
                out << ++id;
                for (int c = 0; c < 20; ++c) {
                    // At most 16 entries per line: the 16th node starts a continuation line.
                    out << (c == 15 ? ",\n" : ", ")
                        << m.node_id(2 * ex + kOffsets[c][0], 2 * ey + kOffsets[c][1],
                                     2 * ez + kOffsets[c][2]);
                }
                out << "\n";
                by_material[material_of(ex, ey, ez)].push_back(id);
            }
    for (std::size_t k = 0; k < materials.size(); ++k) {
        const std::string name = "M" + std::to_string(k + 1);
        write_set(out, "ELSET", name, by_material[static_cast<int>(k)]);
        const Material& mat = materials[k];
        std::snprintf(line, sizeof line,
                      "*MATERIAL, NAME=%s\n*ELASTIC\n%.10g, %.10g\n*DENSITY\n%.10g\n", name.c_str(),
                      mat.e, mat.nu, mat.rho);
        out << line;
        if (mat.cte != 0.0) {
            std::snprintf(line, sizeof line, "*EXPANSION, ZERO=0.\n%.10g\n", mat.cte);
            out << line;
        }
        out << "*SOLID SECTION, ELSET=" << name << ", MATERIAL=" << name << "\n";
    }
}

//! Runs ccx on `inp` (the whole input deck) through the one CalculiX driver of the project
//! (evo/verify/ccx_run.hpp) and returns the displacements of the last *NODE PRINT block.
inline std::map<int, std::array<double, 3>> solve(const std::string& name, const std::string& inp) {
    return evo::run_ccx(name, inp).blocks.back();
}

//! Mean of one displacement component over the given nodes.
inline double mean(const std::map<int, std::array<double, 3>>& u, const std::vector<int>& ids,
                   int component) {
    double sum = 0.0;
    for (int id : ids)
        sum += u.at(id)[component];
    return sum / static_cast<double>(ids.size());
}

}  // namespace bhm::engine::test::ccx
