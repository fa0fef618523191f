#pragma once
// ParaView time series of a replay: series.pvd (the collection, one DataSet per frame with its
// time) + frame-NNNNN.vtu (VTK XML UnstructuredGrid, ASCII: every voxel a VTK_HEXAHEDRON with its
// own 8 corners from its pose and size) + com_path.vtp (VTK XML PolyData: the centre of mass over
// the frames as one polyline, point data time_s). Cell data of each frame: material (1-based),
// fixed (1 = held), displacement (m, centre from the replay's first frame) and
// volumetric_strain (sx sy sz / L^3 - 1).
#include <array>
#include <string>
#include <utility>
#include <vector>

#include "engine/body_spec.hpp"
#include "engine/replay.hpp"
#include "evo/experiment/experiment.hpp"

namespace bhm::evo {

//! A one-frame replay of a body at rest (t = 0): centres at (i + 1/2) L, unrotated, edge L.
engine::Replay rest_replay(const engine::BodySpec& spec);

//! One frame as a .vtu document; reference is the frame displacements are measured from.
std::string vtu_document(const engine::Replay& replay, const engine::VoxelPoses& frame,
                         const engine::VoxelPoses& reference);

//! Mass-weighted centre of mass of a frame (density of each voxel's material; equal volumes).
std::array<double, 3> frame_centre_of_mass(const engine::Replay& replay,
                                           const engine::VoxelPoses& frame,
                                           const std::vector<MaterialEntry>& materials);

//! The COM path as a .vtp polyline (one point per entry, in order).
std::string com_path_vtp(const std::vector<std::array<double, 3>>& com,
                         const std::vector<double>& times_s);

//! The .pvd collection: (time, file name relative to the .pvd) per frame.
std::string pvd_document(const std::vector<std::pair<double, std::string>>& frames);

struct VtkSeriesSummary {
    int frames = 0;
    std::string pvd_path, com_path;
};

//! Writes every `every`-th frame of the replay (and always its last) into dir (created when
//! missing), each file atomically, series.pvd last. Throws std::runtime_error naming the path.
VtkSeriesSummary write_vtk_series(const std::string& dir, const engine::Replay& replay,
                                  const std::vector<MaterialEntry>& materials, int every = 1);

}  // namespace bhm::evo
