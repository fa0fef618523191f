#pragma once
// HyperNEAT's substrate (evolution.algorithm = "hyperneat"; Stanley, D'Ambrosio & Gauci 2009;
// docs/hyperneat.md): a network whose nodes sit at the voxel centres of a lattice and whose
// connection weights a CPPN paints, queried once per connection with the coordinates of its two
// ends. Its outputs per voxel take the place of a direct CPPN's outputs: the body's material
// choice (CppnDecoder::paint) or the controller's phase and amplitude (paint_controller_outputs).
//
// Sheets, each one node per lattice cell at p = the cell's coordinates mapped onto [-1, 1] per
// axis (as cppn_inputs'): an input sheet I (every node 1: a bias sheet; the geometry is in the
// weights), a hidden sheet H and K output sheets O_k (K = the outputs the lattice needs).
// Connections: node b receives from every node a with max(|ax - bx|, |ay - by|, |az - bz|) <=
// radius cells (a local receptive field, itself included), one connection per such pair and sheet
// pair I -> H, H -> H (recurrent) and H -> O_k.
// The CPPN (kHyperNeatInputCount inputs: xa, ya, za, xb, yb, zb, d = |p(b) - p(a)|, bias = 1;
// 2 + K outputs) gives for pair (a, b): output 0 = w(I_a -> H_b), output 1 = w(H_a -> H_b),
// output 2 + k = w(H_a -> O_k b). Expressed weight: the output o itself where |o| >=
// weight_threshold, no connection (0) below it.
// Activation: h(0) = 0; steps times h_b <- tanh(sum_a w_IH(a,b) + sum_a w_HH(a,b) h_a) (all nodes
// at once); then o_k b = sum_a w_HO_k(a,b) h_a, identity, read as a direct CPPN's output k.
#include <array>
#include <cstdint>
#include <vector>

#include "evo/experiment/experiment.hpp"
#include "evo/genome/genome.hpp"

namespace bhm::evo {

//! CPPN outputs before the K output sheets' ones: w(I -> H), w(H -> H).
inline constexpr int kSubstrateHiddenOutputs = 2;

//! The connections of one sheet pair and the CPPN's weights on them, pair p = (source[p],
//! target[p]), grouped by target in cell order, sources in z, y, x order of their offset.
struct SubstrateWeights {
    std::vector<std::int32_t> source, target;
    //! weights[j][p]: CPPN output j for pair p after the threshold (0 = no connection).
    std::vector<std::vector<double>> weights;
};

class HyperNeatSubstrate {
  public:
    //! Throws std::invalid_argument for an empty lattice, radius < 1, steps < 1 or a negative
    //! threshold.
    HyperNeatSubstrate(std::array<int, 3> size, int outputs, const HyperNeatSettings& settings);

    //! CPPN outputs a genome needs: 2 + outputs.
    int cppn_output_count() const { return kSubstrateHiddenOutputs + outputs_; }
    std::size_t cell_count() const { return cells_; }
    std::size_t connection_count() const { return source_.size(); }

    //! The CPPN's expressed weights over every connection (for inspection and tests). Throws
    //! std::invalid_argument when the genome is not a HyperNEAT CPPN with cppn_output_count()
    //! outputs.
    SubstrateWeights weights(const Genome& cppn) const;
    //! The substrate's activated outputs: outputs[k][cell], `outputs` of them.
    std::vector<std::vector<double>> activate(const Genome& cppn) const;

  private:
    std::size_t cells_ = 0;
    int outputs_ = 0;
    HyperNeatSettings settings_;
    std::vector<std::int32_t> source_, target_;
    //! The CPPN's query per connection: kHyperNeatInputCount arrays.
    std::vector<std::vector<double>> query_;
};

}  // namespace bhm::evo
