#include "app/gui/session/fem_verifier.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <stdexcept>
#include <system_error>

#include <cerrno>

#include <fcntl.h>
#include <signal.h>
#include <stdio.h>
#include <unistd.h>

#include <nlohmann/json.hpp>

#include "engine/io/text_file.hpp"
#include "evo/experiment/body_spec_of.hpp"
#include "evo/experiment/experiment_io.hpp"
#include "evo/experiment/json_fields.hpp"
#include "evo/experiment/json_reader.hpp"
#include "evo/verify/ccx_run.hpp"
#include "evo/verify/mesh_error.hpp"
#include "evo/verify/verify_report.hpp"

namespace bhm::app::gui {

namespace fs = std::filesystem;
using nlohmann::json;

namespace {

// Through the capped reader (engine/io/text_file.hpp), like every reader of a run directory: a
// FIFO named report.json would block an std::ifstream's open until a writer came, freezing the
// studio (issue 41 R3); a device or folder would stream or fail with a library's text. Each is
// refused at once as "PATH: reason".
json read_json(const fs::path& path) {
    const std::string text = engine::read_text(path.string(), engine::kTextFileCap);
    try {
        return json::parse(text);
    } catch (const json::exception& e) {
        throw std::runtime_error(path.string() + ": not valid JSON (" +
                                 evo::without_json_tags(e.what()) + ")");
    }
}

// The length of the vector at `key` (a displacement in metres).
double length(const evo::Fields& f, const std::string& key) {
    const auto& v = f.array(key);
    double sum = 0.0;
    for (const auto& x : v) {
        if (!x.is_number()) f.fail(key, "expected an array of numbers");
        sum += x.get<double>() * x.get<double>();
    }
    return std::sqrt(sum);
}

std::optional<double> optional_number(const evo::Fields& f, const json& j, const char* key) {
    if (!j.contains(key) || j.at(key).is_null()) return std::nullopt;
    return f.number(key);
}

// The finished folder replaces the one in place (if any) in one step: RENAME_EXCHANGE swaps the
// two names atomically, so a reader sees the old report or the new one, never neither.
void move_into_place(const fs::path& partial, const fs::path& final_dir) {
    std::error_code ec;
    if (fs::exists(final_dir, ec)) {
        if (::renameat2(AT_FDCWD, partial.c_str(), AT_FDCWD, final_dir.c_str(), RENAME_EXCHANGE) !=
            0)
            throw std::runtime_error("cannot replace " + final_dir.string());
        fs::remove_all(partial, ec);  // the old report, now under the partial name
        return;
    }
    fs::rename(partial, final_dir);
}

// The writer's pid in a partial folder's name (".individual-7.partial-1234-AbC123"); -1 when the
// name has none (written before the pid was part of it).
long partial_owner(const std::string& name) {
    const std::string tag = ".partial-";
    const auto at = name.find(tag);
    if (name.empty() || name[0] != '.' || at == std::string::npos) return -1;
    const auto digits = at + tag.size();
    const auto dash = name.find('-', digits);
    if (dash == std::string::npos || dash == digits) return -1;
    const std::string pid = name.substr(digits, dash - digits);
    if (pid.find_first_not_of("0123456789") != std::string::npos || pid.size() > 9) return -1;
    return std::stol(pid);
}

bool process_gone(long pid) {
    return ::kill(static_cast<pid_t>(pid), 0) != 0 && errno == ESRCH;
}

}  // namespace

int remove_stale_partials(const std::string& run_dir) {
    if (run_dir.empty()) return 0;
    const fs::path verify_dir = fs::path(run_dir) / "verify";
    std::error_code ec;
    fs::directory_iterator it(verify_dir, ec);
    if (ec) return 0;
    const auto now = fs::file_time_type::clock::now();
    int removed = 0;
    for (const auto& entry : it) {
        const std::string name = entry.path().filename().string();
        if (name.empty() || name[0] != '.' || name.find(".partial-") == std::string::npos ||
            !entry.is_directory(ec))
            continue;
        const long owner = partial_owner(name);
        const auto modified = fs::last_write_time(entry.path(), ec);
        const bool old =
            !ec && std::chrono::duration<double>(now - modified).count() > kStalePartialAge_s;
        const bool orphan =
            owner > 0 && owner != static_cast<long>(::getpid()) && process_gone(owner);
        if (!old && !orphan) continue;
        if (fs::remove_all(entry.path(), ec) != static_cast<std::uintmax_t>(-1) && !ec) ++removed;
    }
    return removed;
}

std::string verification_dir(const std::string& run_dir, std::int64_t id) {
    return (fs::path(run_dir) / "verify" / ("individual-" + std::to_string(id))).string();
}

std::vector<std::int64_t> kept_verifications(const std::string& run_dir) {
    std::vector<std::int64_t> ids;
    if (run_dir.empty()) return ids;
    const std::string prefix = "individual-";
    std::error_code ec;
    fs::directory_iterator it(fs::path(run_dir) / "verify", ec);
    if (ec) return ids;
    for (const auto& entry : it) {
        const std::string name = entry.path().filename().string();
        const std::string digits = name.substr(std::min(name.size(), prefix.size()));
        if (name.rfind(prefix, 0) != 0 || digits.empty() || digits.size() > 18 ||
            digits.find_first_not_of("0123456789") != std::string::npos)
            continue;
        if (fs::is_regular_file(entry.path() / "report.json", ec))
            ids.push_back(std::stoll(digits));
    }
    std::sort(ids.begin(), ids.end());
    return ids;
}

std::optional<FemVerification> read_verification(const std::string& dir, std::int64_t id) {
    const fs::path report_path = fs::path(dir) / "report.json";
    std::error_code ec;
    if (!fs::exists(report_path, ec)) return std::nullopt;
    const json r = read_json(report_path);
    FemVerification v;
    v.id = id;
    v.dir = dir;
    // Every field checked before it is read (evo/experiment/json_fields.hpp): a damaged report is
    // "FILE: field: what is wrong" in the FEM tab (issue 41 R9), not a type error without a field.
    try {
        const evo::Fields f(r, "");
        v.verdict = f.string("verdict");
        v.compared = f.string("status") == "compared";
        if (!v.compared) return v;
        if (r.contains("law")) v.law = f.string("law");
        v.agrees = f.boolean("agrees");
        v.worst = f.number("worst_relative_difference");
        v.tolerance = f.number("tolerance");
        const evo::Fields fem(f.at("fem"), "fem");
        v.fem_cpu_s = fem.number("cpu_s");
        v.fem_nodes = static_cast<int>(fem.integer("nodes"));
        v.element = fem.string("element");
        if (r.at("fem").contains("mesh_reason")) v.mesh_reason = fem.string("mesh_reason");
        if (r.contains("fem_mesh_error")) {
            const auto& m = r.at("fem_mesh_error");
            const evo::Fields mf(m, "fem_mesh_error");
            evo::MeshErrorEstimate e;
            e.subdivision = static_cast<int>(mf.integer("elements_per_voxel_edge"));
            if (m.contains("first_elements_per_voxel_edge"))
                e.first_subdivision = static_cast<int>(mf.integer("first_elements_per_voxel_edge"));
            if (m.contains("skipped")) e.skipped = mf.string("skipped");
            if (e.skipped.empty()) e.relative = mf.number("relative_difference");
            v.mesh_error = evo::describe_mesh_error(e);
        }
        v.engine_cpu_s = evo::Fields(f.at("engine"), "engine").number("cpu_s");
        const auto& loads = f.array("loads");
        for (std::size_t k = 0; k < loads.size(); ++k) {
            const std::string where = evo::item("loads", k);
            const evo::Fields l(loads[k], where);
            const evo::Fields lf(l.at("fem"), where + ".fem");
            const evo::Fields le(l.at("engine"), where + ".engine");
            FemLoadRow row;
            row.load = l.string("load");
            row.temperature_c = l.number("temperature_c");
            row.fem_tip_m = length(lf, "tip_displacement_m");
            row.engine_tip_m = length(le, "tip_displacement_m");
            row.fem_bend_deg = lf.number("bend_angle_deg");
            row.engine_bend_deg = le.number("bend_angle_deg");
            row.fem_com_yz_m = length(lf, "com_yz_displacement_m");
            row.engine_com_yz_m = length(le, "com_yz_displacement_m");
            const auto& d = l.at("relative_difference");
            const evo::Fields df(d, where + ".relative_difference");
            row.tip = optional_number(df, d, "tip_displacement");
            row.bend = optional_number(df, d, "bend_angle");
            row.com_yz = optional_number(df, d, "com_yz_displacement");
            row.rms = optional_number(df, d, "voxel_displacement_rms");
            v.rows.push_back(row);
        }
    } catch (const evo::FieldError& e) {
        throw std::runtime_error(report_path.string() + ": " + e.what());
    }
    const fs::path shapes_path = fs::path(dir) / "shapes.json";
    if (fs::exists(shapes_path, ec)) {
        const auto shapes =
            evo::verification_shapes_from_json(read_json(shapes_path), shapes_path.string());
        if (shapes.loads.size() != v.rows.size())
            throw std::runtime_error(shapes_path.string() + ": " +
                                     std::to_string(shapes.loads.size()) +
                                     " loads, the report has " + std::to_string(v.rows.size()));
        v.voxel_cells = shapes.voxel_cells;
        v.fem_shape = shapes.fem;
        v.engine_shape = shapes.engine;
    }
    return v;
}

FemVerifier::~FemVerifier() {
    cancel_ = true;
    if (worker_.joinable()) worker_.join();
}

bool FemVerifier::start(FemVerifyRequest request) {
    if (running_.load()) return false;
    if (worker_.joinable()) worker_.join();  // the last one has ended: reap its thread
    FemVerifyState state;
    state.job = ++jobs_;
    state.id = request.id;
    state.label = request.label;
    state.started = std::chrono::steady_clock::now();
    if (!evo::ccx_available()) {
        // Said at once, in the panel: no thread, no folder, no wait.
        state.phase = FemVerifyPhase::Failed;
        state.error = "ccx (CalculiX) is not on the PATH; install the Debian package calculix-ccx";
        states_.publish(std::make_shared<const FemVerifyState>(state));
        return true;
    }
    state.step = "starting";
    cancel_ = false;
    running_ = true;
    states_.publish(std::make_shared<const FemVerifyState>(state));
    worker_ = std::thread(
        [this, request = std::move(request), state]() mutable { work(std::move(request), state); });
    return true;
}

void FemVerifier::cancel() {
    if (running_.load()) cancel_ = true;
}

void FemVerifier::work(FemVerifyRequest request, FemVerifyState state) {
    auto publish = [&] { states_.publish(std::make_shared<const FemVerifyState>(state)); };
    auto elapsed = [&] {
        return std::chrono::duration<double>(std::chrono::steady_clock::now() - state.started)
            .count();
    };
    fs::path partial;
    remove_stale_partials(request.run_dir);  // what a crash of an earlier one left
    try {
        evo::VerifyOptions options = request.options;
        options.control.cancel = &cancel_;
        options.control.on_progress = [&](const evo::VerifyProgress& p) {
            state.progress = p;
            state.step = evo::describe_progress(p);
            publish();
        };
        const auto spec = evo::make_body_spec(request.experiment, *request.framed_body);
        const auto verification =
            evo::verify_body(spec, request.experiment.fitness.measure, options);
        if (cancel_.load()) throw evo::VerifyCancelled();
        // The FEM's own error from a second mesh (our engine's answer reused): cancellable and
        // reported like the rest.
        const auto mesh_error = evo::estimate_mesh_error(spec, verification, options);
        if (cancel_.load()) throw evo::VerifyCancelled();
        state.step = "writing the report";
        publish();
        const fs::path final_dir = verification_dir(request.run_dir, request.id);
        fs::create_directories(final_dir.parent_path());
        // The pid in the name: a later session removes it only once this process is gone.
        std::string pattern =
            (final_dir.parent_path() / ("." + final_dir.filename().string() + ".partial-" +
                                        std::to_string(::getpid()) + "-XXXXXX"))
                .string();
        if (::mkdtemp(pattern.data()) == nullptr)
            throw std::runtime_error("cannot create a folder in " +
                                     final_dir.parent_path().string());
        partial = pattern;
        nlohmann::json report = evo::write_verification(verification, options, partial.string());
        if (mesh_error) {
            report["fem_mesh_error"] = evo::mesh_error_json(*mesh_error, verification);
            evo::write_file_atomically((partial / "report.json").string(), report.dump(2) + "\n");
        }
        if (cancel_.load()) throw evo::VerifyCancelled();
        move_into_place(partial, final_dir);
        partial.clear();
        auto result = read_verification(final_dir.string(), request.id);
        if (!result) throw std::runtime_error(final_dir.string() + ": no report.json written");
        state.result = std::make_shared<const FemVerification>(std::move(*result));
        state.phase = FemVerifyPhase::Finished;
        state.step = "done";
    } catch (const evo::VerifyCancelled&) {
        state.phase = FemVerifyPhase::Cancelled;
        state.step = "cancelled";
    } catch (const std::exception& e) {
        state.phase = FemVerifyPhase::Failed;
        state.error = evo::without_json_tags(e.what());  // no library's codes in the panel
    }
    if (!partial.empty()) {
        std::error_code ignored;
        fs::remove_all(partial, ignored);
    }
    state.elapsed_s = elapsed();
    publish();  // before running_ drops: whoever sees it idle finds the final state
    running_ = false;
}

}  // namespace bhm::app::gui
