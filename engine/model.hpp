#pragma once
// The immutable model of one body: voxels, links, materials, fixed flags, the time step.
// Built once from a BodySpec, then shared read-only by any number of Worlds (one per thread).
// CONTRACT used by evo/ and render/: keep these public members; the engine may add more.
#include <array>
#include <cstdint>
#include <memory>
#include <vector>

#include "engine/body_spec.hpp"

namespace bhm::engine {

class Model {
public:
    //! Builds the model; throws std::invalid_argument with a one-line reason for a spec that
    //! cannot be simulated (sizes that do not match, material index without a material, ...).
    static std::shared_ptr<const Model> build(const BodySpec& spec);

    int voxel_count() const;
    int link_count() const;
    //! Springs across shared edges between voxels stiffer than both voxels beside that edge
    //! (docs/physics.md, "Springs across edges"); 0 in bodies of one stiffness.
    int edge_spring_count() const;
    double dt_s() const;            //!< dt_fraction x the largest stable step
    double voxel_size_m() const;
    const BodySpec& spec() const;   //!< the spec it was built from

    //! Per voxel v in [0, voxel_count): its lattice cell, coordinates, material (1-based), fixed flag.
    int voxel_cell(int v) const;
    std::array<int, 3> voxel_coords(int v) const;
    int voxel_material(int v) const;
    bool voxel_fixed(int v) const;
    //! Total mass of the body (kg).
    double total_mass_kg() const;

    // Implementation data lives below (structure of arrays); see model.cpp.
    struct Data;
    const Data& data() const { return *data_; }
    explicit Model(std::unique_ptr<Data> data);
    ~Model();

private:
    std::unique_ptr<Data> data_;
};

}  // namespace bhm::engine
