#include "evo/formats/vtk_series.hpp"

#include <unistd.h>

#include <algorithm>
#include <cstdio>
#include <filesystem>
#include <stdexcept>

#include "engine/io/text_file.hpp"
#include "evo/experiment/experiment_io.hpp"

namespace bhm::evo {

namespace {

// Shortest text that reads back as the same float, locale-independent.
void put(std::string& out, float value) {
    out += engine::format_number(value);
    out += ' ';
}
void put(std::string& out, long long value) {
    out += std::to_string(value);
    out += ' ';
}

void rotate(const float* q, const double p[3], double out[3]) {
    const double w = q[0], u[3] = {q[1], q[2], q[3]};
    const double t[3] = {2.0 * (u[1] * p[2] - u[2] * p[1]), 2.0 * (u[2] * p[0] - u[0] * p[2]),
                         2.0 * (u[0] * p[1] - u[1] * p[0])};
    out[0] = p[0] + w * t[0] + (u[1] * t[2] - u[2] * t[1]);
    out[1] = p[1] + w * t[1] + (u[2] * t[0] - u[0] * t[2]);
    out[2] = p[2] + w * t[2] + (u[0] * t[1] - u[1] * t[0]);
}

void check_frame(const engine::Replay& replay, const engine::VoxelPoses& frame) {
    const std::size_t n = replay.voxel_cell.size();
    if (frame.position_m.size() != 3 * n || frame.orientation.size() != 4 * n ||
        frame.size_m.size() != 3 * n || replay.voxel_material.size() != n ||
        replay.voxel_fixed.size() != n)
        throw std::invalid_argument("VTK export: a frame does not match the replay's voxels");
}

}  // namespace

engine::Replay rest_replay(const engine::BodySpec& spec) {
    engine::Replay replay;
    replay.nx = spec.nx;
    replay.ny = spec.ny;
    replay.nz = spec.nz;
    replay.voxel_size_m = spec.voxel_size_m;
    engine::VoxelPoses frame;
    const double L = spec.voxel_size_m;
    for (int c = 0; c < spec.cell_count(); ++c) {
        if (spec.material[c] == 0) continue;
        replay.voxel_cell.push_back(c);
        replay.voxel_material.push_back(spec.material[c]);
        replay.voxel_fixed.push_back(spec.fixed.empty() ? 0 : (spec.fixed[c] ? 1 : 0));
        const int xyz[3] = {c % spec.nx, (c / spec.nx) % spec.ny, c / (spec.nx * spec.ny)};
        for (int a = 0; a < 3; ++a) {
            frame.position_m.push_back(static_cast<float>((xyz[a] + 0.5) * L));
            frame.size_m.push_back(static_cast<float>(L));
        }
        frame.orientation.insert(frame.orientation.end(), {1.0f, 0.0f, 0.0f, 0.0f});
    }
    replay.frames.push_back(std::move(frame));
    return replay;
}

std::string vtu_document(const engine::Replay& replay, const engine::VoxelPoses& frame,
                         const engine::VoxelPoses& reference) {
    check_frame(replay, frame);
    check_frame(replay, reference);
    const std::size_t n = replay.voxel_cell.size();
    std::string out;
    out.reserve(n * 400);
    out +=
        "<?xml version=\"1.0\"?>\n<VTKFile type=\"UnstructuredGrid\" version=\"1.0\" "
        "byte_order=\"LittleEndian\" header_type=\"UInt64\">\n<UnstructuredGrid>\n";
    out += "<Piece NumberOfPoints=\"" + std::to_string(8 * n) + "\" NumberOfCells=\"" +
           std::to_string(n) + "\">\n";
    out += "<Points>\n<DataArray type=\"Float32\" NumberOfComponents=\"3\" format=\"ascii\">\n";
    // VTK_HEXAHEDRON corner order: the bottom face (z-) counter-clockwise, then the top face.
    static constexpr int kCorner[8][3] = {{0, 0, 0}, {1, 0, 0}, {1, 1, 0}, {0, 1, 0},
                                          {0, 0, 1}, {1, 0, 1}, {1, 1, 1}, {0, 1, 1}};
    for (std::size_t v = 0; v < n; ++v) {
        for (const auto& corner : kCorner) {
            double local[3], world[3];
            for (int a = 0; a < 3; ++a)
                local[a] = (corner[a] ? 0.5 : -0.5) * frame.size_m[3 * v + a];
            rotate(&frame.orientation[4 * v], local, world);
            for (int a = 0; a < 3; ++a)
                put(out, static_cast<float>(frame.position_m[3 * v + a] + world[a]));
        }
        out += '\n';
    }
    out +=
        "</DataArray>\n</Points>\n<Cells>\n"
        "<DataArray type=\"Int64\" Name=\"connectivity\" format=\"ascii\">\n";
    for (std::size_t i = 0; i < 8 * n; ++i)
        put(out, static_cast<long long>(i));
    out += "\n</DataArray>\n<DataArray type=\"Int64\" Name=\"offsets\" format=\"ascii\">\n";
    for (std::size_t v = 1; v <= n; ++v)
        put(out, static_cast<long long>(8 * v));
    out += "\n</DataArray>\n<DataArray type=\"UInt8\" Name=\"types\" format=\"ascii\">\n";
    for (std::size_t v = 0; v < n; ++v)
        out += "12 ";
    out +=
        "\n</DataArray>\n</Cells>\n<CellData Scalars=\"material\">\n"
        "<DataArray type=\"Int32\" Name=\"material\" format=\"ascii\">\n";
    for (std::size_t v = 0; v < n; ++v)
        put(out, static_cast<long long>(replay.voxel_material[v]));
    out += "\n</DataArray>\n<DataArray type=\"UInt8\" Name=\"fixed\" format=\"ascii\">\n";
    for (std::size_t v = 0; v < n; ++v)
        put(out, static_cast<long long>(replay.voxel_fixed[v]));
    out +=
        "\n</DataArray>\n<DataArray type=\"Float32\" Name=\"displacement\" "
        "NumberOfComponents=\"3\" format=\"ascii\">\n";
    for (std::size_t i = 0; i < 3 * n; ++i)
        put(out, frame.position_m[i] - reference.position_m[i]);
    out +=
        "\n</DataArray>\n<DataArray type=\"Float32\" Name=\"volumetric_strain\" "
        "format=\"ascii\">\n";
    const double rest_volume = replay.voxel_size_m * replay.voxel_size_m * replay.voxel_size_m;
    for (std::size_t v = 0; v < n; ++v) {
        const double volume = static_cast<double>(frame.size_m[3 * v]) * frame.size_m[3 * v + 1] *
                              frame.size_m[3 * v + 2];
        put(out, static_cast<float>(volume / rest_volume - 1.0));
    }
    out += "\n</DataArray>\n</CellData>\n</Piece>\n</UnstructuredGrid>\n</VTKFile>\n";
    return out;
}

std::array<double, 3> frame_centre_of_mass(const engine::Replay& replay,
                                           const engine::VoxelPoses& frame,
                                           const std::vector<MaterialEntry>& materials) {
    check_frame(replay, frame);
    std::vector<double> density;
    for (const auto& material : materials)
        density.push_back(material.physics.density_kg_m3);
    for (const std::uint8_t m : replay.voxel_material)
        if (m < 1 || m > materials.size())
            throw std::invalid_argument("VTK export: voxel material " + std::to_string(m) +
                                        " is not in the palette");
    return engine::centre_of_mass(frame, engine::voxel_mass_weights(replay, density));
}

std::string com_path_vtp(const std::vector<std::array<double, 3>>& com,
                         const std::vector<double>& times_s) {
    if (com.size() != times_s.size())
        throw std::invalid_argument("VTK export: one time per centre-of-mass point");
    const std::size_t n = com.size();
    std::string out =
        "<?xml version=\"1.0\"?>\n<VTKFile type=\"PolyData\" version=\"1.0\" "
        "byte_order=\"LittleEndian\" header_type=\"UInt64\">\n<PolyData>\n";
    out += "<Piece NumberOfPoints=\"" + std::to_string(n) +
           "\" NumberOfVerts=\"0\" NumberOfLines=\"" + std::string(n > 0 ? "1" : "0") +
           "\" NumberOfStrips=\"0\" NumberOfPolys=\"0\">\n";
    out += "<Points>\n<DataArray type=\"Float32\" NumberOfComponents=\"3\" format=\"ascii\">\n";
    for (const auto& p : com)
        for (double c : p)
            put(out, static_cast<float>(c));
    out +=
        "\n</DataArray>\n</Points>\n<Lines>\n"
        "<DataArray type=\"Int64\" Name=\"connectivity\" format=\"ascii\">\n";
    for (std::size_t i = 0; i < n; ++i)
        put(out, static_cast<long long>(i));
    out += "\n</DataArray>\n<DataArray type=\"Int64\" Name=\"offsets\" format=\"ascii\">\n";
    if (n > 0) put(out, static_cast<long long>(n));
    out +=
        "\n</DataArray>\n</Lines>\n<PointData Scalars=\"time_s\">\n"
        "<DataArray type=\"Float32\" Name=\"time_s\" format=\"ascii\">\n";
    for (double t : times_s)
        put(out, static_cast<float>(t));
    out += "\n</DataArray>\n</PointData>\n</Piece>\n</PolyData>\n</VTKFile>\n";
    return out;
}

std::string pvd_document(const std::vector<std::pair<double, std::string>>& frames) {
    std::string out =
        "<?xml version=\"1.0\"?>\n<VTKFile type=\"Collection\" version=\"0.1\" "
        "byte_order=\"LittleEndian\">\n<Collection>\n";
    for (const auto& [t, file] : frames) {
        out += "<DataSet timestep=\"" + engine::format_number(t) +
               "\" group=\"\" part=\"0\" file=\"" + file + "\"/>\n";
    }
    out += "</Collection>\n</VTKFile>\n";
    return out;
}

namespace fs = std::filesystem;

// The files of a series, written straight into dir (the staging folder).
static VtkSeriesSummary write_series_files(const std::string& dir, const engine::Replay& replay,
                                           const std::vector<MaterialEntry>& materials, int every);

namespace {

bool is_series_file(const std::string& name) {
    return name == "series.pvd" || name == "com_path.vtp" ||
           (name.rfind("frame-", 0) == 0 && name.size() > 4 &&
            name.compare(name.size() - 4, 4, ".vtu") == 0);
}

// Moves the complete new series from staging into dir. The old collection goes first, so from
// then on the folder holds either no series.pvd or the new one: ParaView never loads a mix of
// old and new frames. Files of dir that are not part of a series are left alone.
void swap_in(const fs::path& staging, const fs::path& dir) {
    std::error_code ec;
    fs::remove(dir / "series.pvd", ec);
    for (const auto& entry : fs::directory_iterator(dir))
        if (entry.is_regular_file() && is_series_file(entry.path().filename().string()))
            fs::remove(entry.path());
    std::vector<fs::path> staged;
    for (const auto& entry : fs::directory_iterator(staging))
        staged.push_back(entry.path());
    std::sort(staged.begin(), staged.end(), [](const fs::path& a, const fs::path& b) {
        // series.pvd last: its presence means the frames it lists are in place.
        return (a.filename() == "series.pvd") < (b.filename() == "series.pvd") ||
               ((a.filename() == "series.pvd") == (b.filename() == "series.pvd") && a < b);
    });
    for (const auto& file : staged)
        fs::rename(file, dir / file.filename());
    fs::remove(staging);
}

}  // namespace

VtkSeriesSummary write_vtk_series(const std::string& dir, const engine::Replay& replay,
                                  const std::vector<MaterialEntry>& materials, int every) {
    if (replay.frames.empty()) throw std::runtime_error(dir + ": the replay has no frames");
    if (every < 1) throw std::invalid_argument("VTK export: every must be >= 1");
    std::error_code ec;
    const bool existed = fs::is_directory(dir, ec);
    fs::create_directories(dir, ec);
    if (!fs::is_directory(dir))
        throw std::runtime_error(dir + ": cannot create directory" +
                                 (ec ? " (" + ec.message() + ")" : std::string()));
    // Every file is written into a staging folder first and swapped in whole at the end, so a
    // failure part way (a full disk after frame 0, issue 26 N4) leaves the old series as it was.
    const fs::path staging = fs::path(dir) / (".vtk-staging-" + std::to_string(::getpid()));
    fs::remove_all(staging, ec);
    if (!fs::create_directory(staging, ec))
        throw std::runtime_error(staging.string() + ": cannot create the staging folder (" +
                                 ec.message() + ")");
    try {
        VtkSeriesSummary summary = write_series_files(staging.string(), replay, materials, every);
        swap_in(staging, dir);
        summary.com_path = (fs::path(dir) / "com_path.vtp").string();
        summary.pvd_path = (fs::path(dir) / "series.pvd").string();
        return summary;
    } catch (const std::exception& e) {
        fs::remove_all(staging, ec);
        if (!existed) fs::remove(dir, ec);  // only when empty: it was ours
        const std::string message = e.what();
        // Name the file the user asked for, not the staging copy.
        const std::string staged = staging.string() + "/";
        const auto at = message.find(staged);
        throw std::runtime_error(at == std::string::npos
                                     ? message
                                     : message.substr(0, at) + dir + "/" +
                                           message.substr(at + staged.size()) +
                                           "; the previous series is unchanged");
    }
}

static VtkSeriesSummary write_series_files(const std::string& dir, const engine::Replay& replay,
                                           const std::vector<MaterialEntry>& materials, int every) {
    const fs::path root(dir);
    std::vector<std::pair<double, std::string>> written;
    std::vector<std::array<double, 3>> com;
    std::vector<double> times;
    const std::size_t count = replay.frames.size();
    for (std::size_t f = 0; f < count; ++f) {
        if (f % static_cast<std::size_t>(every) != 0 && f + 1 != count) continue;
        const auto& frame = replay.frames[f];
        char name[32];
        std::snprintf(name, sizeof name, "frame-%05zu.vtu", written.size());
        write_file_atomically((root / name).string(),
                              vtu_document(replay, frame, replay.frames.front()));
        written.emplace_back(frame.time_s, name);
    }
    // The COM path uses every frame, whatever `every` keeps for the meshes.
    for (const auto& frame : replay.frames) {
        com.push_back(frame_centre_of_mass(replay, frame, materials));
        times.push_back(frame.time_s);
    }
    VtkSeriesSummary summary;
    summary.frames = static_cast<int>(written.size());
    summary.com_path = (root / "com_path.vtp").string();
    write_file_atomically(summary.com_path, com_path_vtp(com, times));
    // The collection last: its presence means the frames it lists are complete.
    summary.pvd_path = (root / "series.pvd").string();
    write_file_atomically(summary.pvd_path, pvd_document(written));
    return summary;
}

}  // namespace bhm::evo
