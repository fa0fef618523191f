#pragma once
// Genotype to lattice: evaluates a CPPN at every cell of the design space in one pass, node by
// node over all cells as flat arrays (each node's value computed once, in topological order).
//
// Inputs per cell (paper Table 2): x, y, z = lattice index mapped linearly onto [-1, 1] (0 on an
// axis of one cell); d = Euclidean norm of (x, y, z) mapped linearly from [0, its largest value on
// the lattice] onto [-1, 1]; bias = 1.
// Outputs: identity of the weighted sum (the same decision as a sigmoid thresholded at 0.5):
// material output > 0 puts material in the cell; then active output > 0 picks the active material,
// otherwise the passive one. With per-material outputs (evolution.cppn.material_outputs =
// "per_material"): presence output > 0 fills the cell, with the material whose output is largest
// (the first of equal ones), any of the experiment's materials.
#include <array>
#include <cstdint>
#include <vector>

#include "evo/experiment/experiment.hpp"
#include "evo/genome/genome.hpp"

namespace bhm::evo {

//! The two materials the CPPN chooses between, as 1-based palette indices (0 = the experiment has
//! none). Active = the first material with cte > 0, passive = the first with cte == 0.
struct CppnMaterials {
    std::uint8_t passive = 0;
    std::uint8_t active = 0;
    //! Per-material outputs: output 1 + k paints palette[k]; empty = the two-output layout.
    std::vector<std::uint8_t> palette;
    int output_count() const {
        return palette.empty() ? kOutputCount : 1 + static_cast<int>(palette.size());
    }
};
CppnMaterials cppn_materials(const Experiment& experiment);

class CppnDecoder {
  public:
    CppnDecoder(std::array<int, 3> size, CppnMaterials materials);

    //! The raw lattice (no connectivity filter). Throws std::invalid_argument when a cell needs a
    //! material the experiment lacks (e.g. an active cell and no material with cte > 0) or the
    //! genome's output count is not the decoder's.
    Body decode(const Genome& genome) const;

    const std::array<int, 3>& size() const { return size_; }
    //! Input values per cell, (cells) each, for inspection and tests.
    const std::array<std::vector<double>, kInputCount>& inputs() const { return inputs_; }

  private:
    std::array<int, 3> size_;
    CppnMaterials materials_;
    std::array<std::vector<double>, kInputCount> inputs_;
};

}  // namespace bhm::evo
