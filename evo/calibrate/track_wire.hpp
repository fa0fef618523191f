#pragma once
// Byte messages for a calibration's simulations in another process: what the MPI front end of
// `bhm calibrate` (app/mpi/mpi_track_batches.*) carries between rank 0 and the other ranks. Pure
// C++ (no MPI here), so the round trips are tested without a launcher.
//
// Every message starts with "BHMT", a u16 wire version and a u8 kind; integers little-endian,
// doubles as their 8 bytes (so every value comes back bit for bit).
//  - Setup: requested threads per rank, the --fit list, the experiment as
//    evo/evaluate/evaluation_wire.hpp's rules message (its exact round trip checked), the body
//    (3 x i32 size, one byte per cell) and the track (times; per point name, kind, cell, axes,
//    positions).
//  - Job: batch, index, x (the fit's parameter vector).
//  - Result: batch, index, the simulated track (diverged, reason, wall_s, positions).
#include <cstdint>
#include <string>
#include <vector>

#include "evo/calibrate/measured_track.hpp"
#include "evo/calibrate/track_simulation.hpp"
#include "evo/experiment/experiment.hpp"

namespace bhm::evo {

// Version 2: the setup's body carries its per-voxel fibre axes (Body::fibre) after its cells.
inline constexpr std::uint16_t kTrackWireVersion = 2;

struct TrackSetupMessage {
    std::int32_t requested_threads = 0;  //!< per rank; 0 = all cores of that rank's node
    std::string fit_list;                //!< as --fit takes it ("E,amplitude")
    Experiment experiment;
    Body framed_body;
    MeasuredTrack track;
};
struct TrackJobMessage {
    std::uint64_t batch = 0;
    std::uint32_t index = 0;
    std::vector<double> x;
};
struct TrackResultMessage {
    std::uint64_t batch = 0;
    std::uint32_t index = 0;
    SimulatedTrack track;
};

//! encode_track_setup throws WireError (evaluation_wire.hpp) when the experiment would not come
//! back identical from its JSON.
std::string encode_track_setup(const TrackSetupMessage& message);
std::string encode_track_job(const TrackJobMessage& message);
std::string encode_track_result(const TrackResultMessage& message);
//! Each throws WireError naming what is wrong (magic, version, kind, truncation).
TrackSetupMessage decode_track_setup(const std::string& bytes);
TrackJobMessage decode_track_job(const std::string& bytes);
TrackResultMessage decode_track_result(const std::string& bytes);

}  // namespace bhm::evo
