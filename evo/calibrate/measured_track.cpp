#include "evo/calibrate/measured_track.hpp"

#include <cerrno>
#include <cmath>
#include <cstdlib>
#include <fstream>
#include <map>
#include <sstream>
#include <stdexcept>
#include <string_view>

#include "engine/io/text_file.hpp"

namespace bhm::evo {

namespace {

// Positions beyond this in metres are taken for pixels or millimetres written as metres.
constexpr double kMaxPlausibleMetres = 10.0;
constexpr std::size_t kMinRows = 3;

std::string trim(const std::string& s) {
    const auto a = s.find_first_not_of(" \t\r");
    if (a == std::string::npos) return {};
    const auto b = s.find_last_not_of(" \t\r");
    return s.substr(a, b - a + 1);
}

std::vector<std::string> split_commas(const std::string& line) {
    std::vector<std::string> out;
    std::stringstream in(line);
    std::string cell;
    while (std::getline(in, cell, ',')) out.push_back(trim(cell));
    if (!line.empty() && line.back() == ',') out.emplace_back();
    return out;
}

// A number or nullopt-like failure: returns false for anything strtod does not consume whole.
bool parse_number(const std::string& s, double& out) {
    if (s.empty()) return false;
    errno = 0;
    char* end = nullptr;
    out = std::strtod(s.c_str(), &end);
    return end == s.c_str() + s.size() && errno != ERANGE;
}

struct Directives {
    std::string units = "m";
    double scale_m_per_px = 0.0;
    double time_offset_s = 0.0;
};

// "# key: value" lines before the header; other comment lines are free text.
void read_directive(const std::string& line, Directives& d, const std::string& where) {
    const std::string body = trim(line.substr(1));
    const auto colon = body.find(':');
    if (colon == std::string::npos) return;
    const std::string key = trim(body.substr(0, colon));
    const std::string value = trim(body.substr(colon + 1));
    double number = 0.0;
    if (key == "units") {
        if (value != "m" && value != "px")
            throw std::runtime_error(where + ": units '" + value +
                                     "' is not supported (use m, or px with scale_m_per_px)");
        d.units = value;
    } else if (key == "scale_m_per_px") {
        if (!parse_number(value, number) || !(number > 0.0) || !std::isfinite(number))
            throw std::runtime_error(where + ": scale_m_per_px must be a positive number, got '" +
                                     value + "'");
        d.scale_m_per_px = number;
    } else if (key == "time_offset_s") {
        if (!parse_number(value, number) || !std::isfinite(number))
            throw std::runtime_error(where + ": time_offset_s must be a number, got '" + value +
                                     "'");
        d.time_offset_s = number;
    }
}

// "tip.x" -> point "tip", axis 0. Throws naming the column.
std::pair<std::string, int> column_of(const std::string& name, const std::string& where) {
    const auto dot = name.rfind('.');
    const std::string axis = dot == std::string::npos ? "" : name.substr(dot + 1);
    const int a = axis == "x" ? 0 : axis == "y" ? 1 : axis == "z" ? 2 : -1;
    if (a < 0)
        throw std::runtime_error(where + ": column '" + name +
                                 "' is not POINT.x, POINT.y or POINT.z");
    return {name.substr(0, dot), a};
}

TrackPoint point_named(const std::string& name, const std::string& where) {
    TrackPoint p;
    p.name = name;
    if (name == "tip") {
        p.kind = TrackPointKind::Tip;
    } else if (name == "com") {
        p.kind = TrackPointKind::Com;
    } else if (name.rfind("voxel:", 0) == 0) {
        double n = -1.0;
        if (!parse_number(name.substr(6), n) || n < 0.0 || n != std::floor(n) || n > 1e9)
            throw std::runtime_error(where + ": point '" + name +
                                     "' needs a lattice cell index, as in voxel:12");
        p.kind = TrackPointKind::Voxel;
        p.cell = static_cast<int>(n);
    } else {
        throw std::runtime_error(where + ": unknown point '" + name +
                                 "' (tip, com or voxel:N)");
    }
    return p;
}

}  // namespace

std::size_t MeasuredTrack::compared_values() const {
    std::size_t n = 0;
    for (const auto& p : points)
        for (bool a : p.axes) n += a ? t_s.size() : 0;
    return n;
}

MeasuredTrack parse_measured_track(const std::string& text, const std::string& label) {
    MeasuredTrack track;
    track.source = label;
    Directives d;
    // Spreadsheets save "CSV UTF-8" with a byte order mark before the first line: it is not part
    // of the header (or comment) it precedes.
    constexpr std::string_view kUtf8Bom = "\xEF\xBB\xBF";
    std::istringstream in(text.starts_with(kUtf8Bom) ? text.substr(kUtf8Bom.size()) : text);
    std::string line;
    int line_no = 0;
    bool have_header = false;
    std::vector<std::pair<int, int>> columns;  // (point index, axis) per column after t_s
    int data_row = 0;
    while (std::getline(in, line)) {
        ++line_no;
        const std::string where = label + ": line " + std::to_string(line_no);
        // Refused before any of the line is quoted in a message: what() ends at a NUL, so an
        // error quoting a cell with one lost its own end (issue 41 R8). A UTF-16 file has one in
        // every character.
        if (const auto nul = line.find('\0'); nul != std::string::npos)
            throw std::runtime_error(where + ": a NUL byte at character " +
                                     std::to_string(nul + 1) +
                                     " (a track is text: save a UTF-16 file as CSV UTF-8)");
        const std::string t = trim(line);
        if (t.empty()) continue;
        if (t[0] == '#') {
            if (have_header)
                continue;
            read_directive(t, d, where);
            continue;
        }
        const auto cells = split_commas(t);
        if (!have_header) {
            if (cells.empty() || cells[0] != "t_s")
                throw std::runtime_error(where + ": the header must start with t_s");
            std::map<std::string, int> index;
            for (std::size_t c = 1; c < cells.size(); ++c) {
                const auto [name, axis] = column_of(cells[c], where);
                if (!index.count(name)) {
                    index[name] = static_cast<int>(track.points.size());
                    track.points.push_back(point_named(name, where));
                }
                TrackPoint& p = track.points[static_cast<std::size_t>(index[name])];
                if (p.axes[static_cast<std::size_t>(axis)])
                    throw std::runtime_error(where + ": column '" + cells[c] + "' appears twice");
                p.axes[static_cast<std::size_t>(axis)] = true;
                columns.emplace_back(index[name], axis);
            }
            if (columns.empty())
                throw std::runtime_error(where + ": the header names no point column");
            if (d.units == "px" && d.scale_m_per_px <= 0.0)
                throw std::runtime_error(label + ": units px needs '# scale_m_per_px: S'");
            have_header = true;
            continue;
        }
        ++data_row;
        const std::string row = label + ": row " + std::to_string(data_row) + " (line " +
                                std::to_string(line_no) + ")";
        if (cells.size() != columns.size() + 1)
            throw std::runtime_error(row + ": has " + std::to_string(cells.size()) +
                                     " values, the header has " +
                                     std::to_string(columns.size() + 1));
        std::vector<double> values(cells.size());
        for (std::size_t c = 0; c < cells.size(); ++c) {
            if (!parse_number(cells[c], values[c]))
                throw std::runtime_error(row + ": '" + cells[c] + "' is not a number");
            if (!std::isfinite(values[c]))
                throw std::runtime_error(row + ": " + (c == 0 ? std::string("t_s") : "a position") +
                                         " is not finite (" + cells[c] + ")");
        }
        const double t_s = values[0] + d.time_offset_s;
        if (t_s < 0.0)
            throw std::runtime_error(row + ": time " + cells[0] +
                                     " s is before the simulation starts (with time_offset_s)");
        if (!track.t_s.empty() && !(t_s > track.t_s.back()))
            throw std::runtime_error(row + ": time " + cells[0] +
                                     " s is not after the previous row's (times must increase)");
        track.t_s.push_back(t_s);
        for (auto& p : track.points) p.position_m.push_back({0.0, 0.0, 0.0});
        for (std::size_t c = 1; c < cells.size(); ++c) {
            const auto [pi, axis] = columns[c - 1];
            double v = values[c];
            if (d.units == "px") {
                v *= d.scale_m_per_px;
            } else if (std::abs(v) > kMaxPlausibleMetres) {
                throw std::runtime_error(row + ": " + cells[c] +
                                         " m is implausible for a position in metres (pixels "
                                         "need '# units: px' and '# scale_m_per_px: S')");
            }
            track.points[static_cast<std::size_t>(pi)].position_m.back()[static_cast<std::size_t>(
                axis)] = v;
        }
    }
    if (!have_header) throw std::runtime_error(label + ": no header line (t_s,POINT.x,...)");
    track.time_offset_s = d.time_offset_s;
    if (track.t_s.size() < kMinRows)
        throw std::runtime_error(label + ": row " + std::to_string(track.t_s.size()) +
                                 ": too short, a track needs at least " +
                                 std::to_string(kMinRows) + " rows");
    return track;
}

MeasuredTrack load_measured_track(const std::string& path) {
    // engine::read_text's FileReadError is "PATH: reason" (missing, not a regular file, too big).
    return parse_measured_track(engine::read_text(path), path);
}

std::string measured_track_to_csv(const MeasuredTrack& track, const std::string& comment) {
    std::ostringstream out;
    out.precision(9);
    std::istringstream lines(comment);
    std::string line;
    while (std::getline(lines, line)) out << "# " << line << "\n";
    out << "# units: m\nt_s";
    const char* axis_names[3] = {"x", "y", "z"};
    for (const auto& p : track.points)
        for (int a = 0; a < 3; ++a)
            if (p.axes[static_cast<std::size_t>(a)]) out << "," << p.name << "." << axis_names[a];
    out << "\n";
    for (std::size_t k = 0; k < track.t_s.size(); ++k) {
        out << track.t_s[k];
        for (const auto& p : track.points)
            for (std::size_t a = 0; a < 3; ++a)
                if (p.axes[a]) out << "," << p.position_m[k][a];
        out << "\n";
    }
    return out.str();
}

}  // namespace bhm::evo
