#pragma once
// Genotype to phenotype (paper section 3): the CPPN paints the design space (the workspace minus
// the enclosure frame), only the largest face-connected component is kept, then the lead's
// apply_frame_and_overrides adds the frame and the voxel overrides. The result, the size of the
// workspace, is what gets simulated and what identifies an individual.
#include <array>
#include <cstdint>
#include <memory>
#include <string>

#include "evo/experiment/experiment.hpp"
#include "evo/genome/cppn_decoder.hpp"
#include "evo/genome/genome.hpp"
#include "evo/genome/hyperneat_substrate.hpp"

namespace bhm::evo {

//! The box of the workspace the CPPN designs: the workspace minus the frame thickness per face.
struct DesignSpace {
    std::array<int, 3> origin{0, 0, 0};  //!< first cell in the workspace
    std::array<int, 3> size{0, 0, 0};
    int cell_count() const { return size[0] * size[1] * size[2]; }
    bool contains(int x, int y, int z) const {
        return x >= origin[0] && x < origin[0] + size[0] && y >= origin[1] &&
               y < origin[1] + size[1] && z >= origin[2] && z < origin[2] + size[2];
    }
};
DesignSpace design_space(const Experiment& experiment);

struct Phenotype {
    Body body;                //!< framed, workspace-sized: what is simulated
    std::uint64_t hash = 0;   //!< hash_body(body)
    int voxels = 0;           //!< filled cells of body
    int active_voxels = 0;    //!< cells of body with an active material
    int designed_voxels = 0;  //!< filled cells of body inside the design space
    bool operator==(const Phenotype& other) const {
        return hash == other.hash && body.cells == other.body.cells &&
               body.fibre == other.body.fibre && body.phase == other.body.phase &&
               body.amplitude == other.body.amplitude;
    }
};

//! Develops genomes for one experiment. Cheap to copy; decode is const and thread-safe.
class Developer {
  public:
    //! Throws std::invalid_argument when the experiment lacks a passive or an active material
    //! (the CPPN's two outputs need both) or its design space is empty.
    explicit Developer(const Experiment& experiment);

    //! The genome's phenotype. With evolution.controller fixed_body the genome is a controller
    //! (evo/genome/controller.hpp) and the phenotype is the fixed body, framed, painted by it.
    //! With evolution.algorithm hyperneat the genome is a HyperNEAT CPPN and the substrate's
    //! outputs (hyperneat_substrate.hpp) take the place of a direct CPPN's, for the body or, in
    //! fixed_body, for the controller.
    Phenotype develop(const Genome& genome) const;
    //! evolution.controller coevolve: develop(genome) with `controller` painted on the body; in
    //! any other mode the controller is ignored (develop(genome)).
    Phenotype develop(const Genome& genome, const Genome& controller) const;
    //! The lattice the CPPN paints, before the connectivity filter (for inspection and tests).
    Body decode_raw(const Genome& genome) const;

    const DesignSpace& space() const { return space_; }
    //! Outputs the experiment's CPPN has (Genome::output_count of every genome it develops).
    int cppn_output_count() const { return output_count_; }
    //! Inputs it has: kInputCount, or kHyperNeatInputCount under HyperNEAT.
    int cppn_input_count() const { return input_count_; }
    //! HyperNEAT's substrate; null for the other algorithms.
    const HyperNeatSubstrate* substrate() const { return substrate_.get(); }
    const Experiment& experiment() const { return experiment_; }
    ControllerMode controller_mode() const { return experiment_.evolution.controller.mode; }

  private:
    //! hash, voxel counts of p.body
    void count(Phenotype& p) const;

    Experiment experiment_;
    DesignSpace space_;
    CppnDecoder decoder_;
    int output_count_ = kOutputCount;
    int input_count_ = kInputCount;
    //! Shared by copies: its precomputed queries are the large part (connections x 8 values).
    std::shared_ptr<const HyperNeatSubstrate> substrate_;
    Body fixed_framed_;  //!< fixed_body: the body, framed (apply_frame_and_overrides)
};

}  // namespace bhm::evo
