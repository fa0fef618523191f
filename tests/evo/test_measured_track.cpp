// The measured-track reader (docs/track-format.md): what it accepts and the one-line errors that
// name the row for what it does not.
#include <doctest/doctest.h>

#include <stdexcept>
#include <string>

#include "evo/calibrate/measured_track.hpp"

using bhm::evo::parse_measured_track;

namespace {

// The message of the error parsing text raises ("" when it parses).
std::string error_of(const std::string& text) {
    try {
        parse_measured_track(text, "t.csv");
    } catch (const std::runtime_error& e) {
        return e.what();
    }
    return "";
}

}  // namespace

TEST_CASE("a track in pixels with a scale and a time offset reads in metres and simulation time") {
    const auto track = parse_measured_track(
        "# from a tracker\n# units: px\n# scale_m_per_px: 0.0005\n# time_offset_s: 1.5\n"
        "t_s,tip.x,tip.z,com.x,com.y,com.z,voxel:7.y\n"
        "0.0, 100, 40, 1, 2, 3, 5\n"
        "0.1, 102, 38, 1, 2, 3, 5\n"
        "0.2, 104, 36, 1, 2, 3, 6\n",
        "t.csv");
    REQUIRE(track.t_s.size() == 3);
    CHECK(track.t_s[1] == doctest::Approx(1.6));
    REQUIRE(track.points.size() == 3);
    CHECK(track.points[0].name == "tip");
    CHECK(track.points[0].axes == std::array<bool, 3>{true, false, true});
    CHECK(track.points[0].position_m[2][0] == doctest::Approx(104 * 0.0005));
    CHECK(track.points[0].position_m[2][2] == doctest::Approx(36 * 0.0005));
    CHECK(track.points[2].kind == bhm::evo::TrackPointKind::Voxel);
    CHECK(track.points[2].cell == 7);
    // 3 rows x (2 + 3 + 1) axes
    CHECK(track.compared_values() == 18);
}

TEST_CASE("bad tracks give one-line errors naming the row") {
    const std::string header = "# units: m\nt_s,tip.x\n";
    CHECK(error_of(header + "0,0\n0.1,0.001\n") ==
          "t.csv: row 2: too short, a track needs at least 3 rows");
    CHECK(error_of(header + "0,0\n0.2,0.001\n0.1,0.002\n") ==
          "t.csv: row 3 (line 5): time 0.1 s is not after the previous row's (times must "
          "increase)");
    CHECK(error_of(header + "0,0\n0.1,nan\n0.2,0\n") ==
          "t.csv: row 2 (line 4): a position is not finite (nan)");
    CHECK(error_of(header + "0,0\n0.1,abc\n0.2,0\n") ==
          "t.csv: row 2 (line 4): 'abc' is not a number");
    CHECK(error_of(header + "0,0\n0.1\n0.2,0\n") ==
          "t.csv: row 2 (line 4): has 1 values, the header has 2");
    // Pixels written as metres.
    CHECK(error_of(header + "0,0\n0.1,412\n0.2,0\n") ==
          "t.csv: row 2 (line 4): 412 m is implausible for a position in metres (pixels need "
          "'# units: px' and '# scale_m_per_px: S')");
    CHECK(error_of("# units: mm\nt_s,tip.x\n0,0\n1,0\n2,0\n") ==
          "t.csv: line 1: units 'mm' is not supported (use m, or px with scale_m_per_px)");
    CHECK(error_of("# units: px\nt_s,tip.x\n0,0\n1,0\n2,0\n") ==
          "t.csv: units px needs '# scale_m_per_px: S'");
    CHECK(error_of("t_s,knee.x\n0,0\n1,0\n2,0\n") ==
          "t.csv: line 1: unknown point 'knee' (tip, com or voxel:N)");
    CHECK(error_of("t_s,tip.w\n0,0\n1,0\n2,0\n") ==
          "t.csv: line 1: column 'tip.w' is not POINT.x, POINT.y or POINT.z");
    CHECK(error_of("time,tip.x\n0,0\n1,0\n2,0\n") == "t.csv: line 1: the header must start with t_s");
    CHECK(error_of("# time_offset_s: -1\nt_s,tip.x\n0,0\n1,0\n2,0\n") ==
          "t.csv: row 1 (line 3): time 0 s is before the simulation starts (with time_offset_s)");
}

TEST_CASE("a track written by measured_track_to_csv reads back the same") {
    const auto track = parse_measured_track("t_s,com.x,com.z\n0,0.01,0.02\n0.5,0.011,0.019\n1,0.012,0.018\n",
                                            "t.csv");
    const auto again = parse_measured_track(bhm::evo::measured_track_to_csv(track, "note"), "u.csv");
    CHECK(again.t_s == track.t_s);
    CHECK(again.points[0].position_m == track.points[0].position_m);
    CHECK(again.points[0].axes == track.points[0].axes);
}

TEST_CASE("a track file that cannot be read is one line naming it, and a folder is refused") {
    auto error_of = [](const std::string& path) -> std::string {
        try {
            (void)bhm::evo::load_measured_track(path);
        } catch (const std::runtime_error& e) {
            return e.what();
        }
        return "";
    };
    const std::string missing = std::string(BHM_SOURCE_DIR) + "/tests/data/no-such-track.csv";
    CHECK(error_of(missing) == missing + ": no such file");
    // A folder opens as a stream but reads nothing: refused by name, not parsed as an empty track.
    const std::string folder = std::string(BHM_SOURCE_DIR) + "/tests/data";
    CHECK(error_of(folder) == folder + ": is a directory, not a file");
}

TEST_CASE("a track saved as CSV UTF-8 with a byte order mark reads as the same track without") {
    const std::string text = "# units: m\nt_s,tip.x\n0,0\n0.1,0.001\n0.2,0.002\n";
    const auto plain = parse_measured_track(text, "t.csv");
    const auto marked = parse_measured_track("\xEF\xBB\xBF" + text, "t.csv");
    CHECK(marked.t_s == plain.t_s);
    CHECK(marked.points[0].position_m == plain.points[0].position_m);
    // And where the header itself is the first line.
    CHECK(parse_measured_track("\xEF\xBB\xBFt_s,tip.x\n0,0\n0.1,0\n0.2,0\n", "t.csv").t_s.size() ==
          3);
    // Only at the start: elsewhere it is a bad cell like any other.
    CHECK(error_of("t_s,tip.x\n0,0\n\xEF\xBB\xBF" "0.1,0\n0.2,0\n") ==
          "t.csv: row 2 (line 3): '\xEF\xBB\xBF" "0.1' is not a number");
}

TEST_CASE("a NUL byte in a track is an error that names the file and the line, whole") {
    using namespace std::string_literals;
    const std::string nul_cell = "t_s,tip.x\n0,0\n0.1,0\0x\n0.2,0\n"s;
    CHECK(error_of(nul_cell) ==
          "t.csv: line 3: a NUL byte at character 6 (a track is text: save a UTF-16 file as CSV "
          "UTF-8)");
    // In the header's column names and in a directive's value, where it used to be quoted.
    CHECK(error_of("t_s,tip\0.x\n0,0\n0.1,0\n0.2,0\n"s).starts_with("t.csv: line 1: a NUL byte"));
    CHECK(error_of("# time_offset_s: 1\0\nt_s,tip.x\n0,0\n0.1,0\n0.2,0\n"s)
              .ends_with("save a UTF-16 file as CSV UTF-8)"));
    // A spreadsheet's "Unicode text": UTF-16 LE with its byte order mark.
    std::string utf16 = "\xFF\xFE"s;
    for (char c : "t_s,tip.x\n0,0\n"s) utf16 += std::string{c, '\0'};
    CHECK(error_of(utf16).starts_with("t.csv: line 1: a NUL byte at character 4 "));
}
