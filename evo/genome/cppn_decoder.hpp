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
// Fibre outputs (evolution.cppn.fibre_outputs, issue 43): three more outputs after those, one per
// lattice axis; a cell of a muscle material takes the axis whose output is largest (the first of
// equal ones) as its own fibre axis (Body::fibre); other cells keep kMaterialFibreAxis. Argmax
// of three rather than one output cut in thirds: no axis lies between the other two, so x and z
// are as near each other as either is to y, and each axis gets its own pattern to paint (three
// regions of one output would order the axes x < y < z along it and favour the middle one).
#include <array>
#include <cstdint>
#include <span>
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

//! Fibre outputs: muscle[k] is 1 where material k (1-based; muscle[0] unused) is an active muscle
//! material, whose cells take an axis from the last three outputs; empty = no fibre outputs.
struct CppnFibres {
    std::vector<std::uint8_t> muscle;
    bool enabled() const { return !muscle.empty(); }
    int output_count() const { return enabled() ? 3 : 0; }
};
//! Empty unless the experiment sets evolution.cppn.fibre_outputs.
CppnFibres cppn_fibres(const Experiment& experiment);

//! The CPPN's inputs (x, y, z, d, bias as above) at every cell of a lattice of this size.
std::array<std::vector<double>, kInputCount> cppn_inputs(std::array<int, 3> size);
//! Every node's value at every cell (value[node][cell]) for these inputs, nodes in topological
//! order, each cell's sums in genome edge order (so reproducible). Throws on a cyclic genome or
//! when inputs.size() is not genome.input_count. A "cell" is any query point: a lattice cell, or a
//! pair of substrate nodes for HyperNEAT (evo/genome/hyperneat_substrate.hpp).
std::vector<std::vector<double>> cppn_node_values(const Genome& genome,
                                                  std::span<const std::vector<double>> inputs);

class CppnDecoder {
  public:
    CppnDecoder(std::array<int, 3> size, CppnMaterials materials, CppnFibres fibres = {});
    //! Outputs a genome needs: the material outputs, then the fibre outputs.
    int output_count() const { return materials_.output_count() + fibres_.output_count(); }

    //! The raw lattice (no connectivity filter). Throws std::invalid_argument when a cell needs a
    //! material the experiment lacks (e.g. an active cell and no material with cte > 0) or the
    //! genome's output count is not the decoder's.
    Body decode(const Genome& genome) const;
    //! The raw lattice from output values given directly (outputs[k][cell], output_count() of
    //! them): what decode does after evaluating the CPPN; HyperNEAT's substrate supplies them.
    Body paint(const std::vector<std::vector<double>>& outputs) const;

    const std::array<int, 3>& size() const { return size_; }
    //! Input values per cell, (cells) each, for inspection and tests.
    const std::array<std::vector<double>, kInputCount>& inputs() const { return inputs_; }

  private:
    //! body.cells and body.fibre from output values (output k at value[kInputCount + k]).
    Body paint_values(const std::vector<std::vector<double>>& value) const;
    //! body.cells from the material outputs (value as paint_values').
    void paint_materials(const std::vector<std::vector<double>>& value, Body& body) const;

    std::array<int, 3> size_;
    CppnMaterials materials_;
    CppnFibres fibres_;
    std::array<std::vector<double>, kInputCount> inputs_;
};

}  // namespace bhm::evo
