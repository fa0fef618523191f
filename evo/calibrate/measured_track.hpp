#pragma once
// A measured track (docs/track-format.md): the positions of a few named points of a prototype
// (tip, centre of mass, or one voxel) over time, as a tracker reads them off a video. Read
// strictly: every bad row gives a one-line error naming the file and the row.
#include <array>
#include <string>
#include <vector>

namespace bhm::evo {

enum class TrackPointKind { Tip, Com, Voxel };

//! One tracked point: its positions at every time of the track, in metres (converted from pixels
//! where the file is in pixels). Only the axes the file gives are compared.
struct TrackPoint {
    std::string name;  //!< "tip", "com" or "voxel:N"
    TrackPointKind kind = TrackPointKind::Tip;
    int cell = -1;                        //!< lattice cell index for voxel:N
    std::array<bool, 3> axes{};           //!< x, y, z present
    std::vector<std::array<double, 3>> position_m;  //!< (times); absent axes are 0
};

struct MeasuredTrack {
    std::vector<double> t_s;  //!< simulation time of each row (file time + time_offset_s), increasing
    std::vector<TrackPoint> points;
    std::string source;  //!< the file it was read from (for messages)
    //! The header's time_offset_s, already in t_s: for messages that name the field that set the
    //! track's span (track_wire does not carry it).
    double time_offset_s = 0.0;
    std::size_t compared_values() const;  //!< rows x present axes over every point
};

//! Parses a track; label names the source in errors. Throws std::runtime_error
//! "LABEL: row N: why" (or "LABEL: why" for the header).
MeasuredTrack parse_measured_track(const std::string& text, const std::string& label);
MeasuredTrack load_measured_track(const std::string& path);
//! Writes a track in metres (header, one row per time): for the example asset and tests.
std::string measured_track_to_csv(const MeasuredTrack& track, const std::string& comment);

}  // namespace bhm::evo
