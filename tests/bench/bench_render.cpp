// Renderer speed: frames per second for a 2,000-voxel body at 1280x720 on OSMesa (llvmpipe).
// The studio needs >= 30 fps with one core left to it (evolution runs on the other): run with
// LP_NUM_THREADS=1 to measure that case. Cases: build_draw_list (CPU only), frame_draw (draw list
// + draw + glFinish, the camera orbiting: a studio frame), frame_draw_readback (draw + resolve +
// read the pixels: a bhm render video frame before encoding); each at rest (hidden faces culled)
// and deformed (every voxel moved, turned and resized: most shared faces must be drawn), with 1
// and 4 samples per pixel. CSV on stdout (also to --out FILE); the commit comes from $BHM_COMMIT.
//   bench_render [--frames N] [--size WxH] [--out results.csv]
#include <glad/gl.h>

#include <chrono>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <fstream>
#include <iostream>
#include <sstream>
#include <string>

#include "render/draw_list.hpp"
#include "render/offscreen.hpp"
#include "render/renderer.hpp"

namespace {

using namespace bhm::render;
using Clock = std::chrono::steady_clock;

// A 20 x 10 x 10 block (2,000 voxels) of alternating muscle and tissue, every voxel slightly
// moved, turned and resized as in a running simulation, its x = 0 layer held.
Scene benchmark_scene(bool deformed) {
    bhm::engine::BodySpec spec;
    spec.nx = 20, spec.ny = 10, spec.nz = 10;
    spec.material.assign(static_cast<std::size_t>(spec.cell_count()), 2);
    spec.fixed.assign(static_cast<std::size_t>(spec.cell_count()), 0);
    for (int c = 0; c < spec.cell_count(); ++c) {
        const int x = c % spec.nx, y = (c / spec.nx) % spec.ny, z = c / (spec.nx * spec.ny);
        if ((x / 2 + y / 2 + z / 2) % 2 == 0) spec.material[static_cast<std::size_t>(c)] = 1;
        spec.fixed[static_cast<std::size_t>(c)] = x == 0;
    }
    Scene scene;
    scene.body = body_view_from_spec(spec);
    auto& poses = scene.body.poses;
    for (int v = 0; deformed && v < scene.body.voxel_count(); ++v) {
        const std::size_t i = static_cast<std::size_t>(v);
        const float phase = 0.37f * static_cast<float>(v);
        poses.position_m[3 * i + 2] += 0.001f * std::sin(phase);
        const float angle = 0.05f * std::sin(1.3f * phase);
        poses.orientation[4 * i] = std::cos(0.5f * angle);
        poses.orientation[4 * i + 2] = std::sin(0.5f * angle);
        poses.size_m[3 * i] *= 1.0f + 0.05f * std::sin(phase);
    }
    scene.workspace = {24, 12, 12};
    scene.material_colors = {palette::kActive, palette::kPassive};
    scene.faces[0] = FaceMarking::Fixed;
    scene.faces[1] = FaceMarking::Free;
    return scene;
}

double seconds_since(Clock::time_point start) {
    return std::chrono::duration<double>(Clock::now() - start).count();
}

}  // namespace

int main(int argc, char** argv) {
    int frames = 60, width = 1280, height = 720;
    std::string out_path;
    for (int i = 1; i < argc; ++i) {
        const std::string arg = argv[i];
        if (arg == "--frames" && i + 1 < argc) {
            frames = std::atoi(argv[++i]);
        } else if (arg == "--size" && i + 1 < argc) {
            if (std::sscanf(argv[++i], "%dx%d", &width, &height) != 2) {
                std::cerr << "bench_render: --size wants WxH\n";
                return 2;
            }
        } else if (arg == "--out" && i + 1 < argc) {
            out_path = argv[++i];
        } else {
            std::cerr << "usage: bench_render [--frames N] [--size WxH] [--out FILE]\n";
            return 2;
        }
    }
    const char* threads = std::getenv("LP_NUM_THREADS");
    const char* env_commit = std::getenv("BHM_COMMIT");  // set by scripts/bench.sh
    const std::string commit = env_commit ? env_commit : "unknown";
    std::ostringstream csv;
    csv << "case,pose,voxels,width,height,samples,lp_threads,frames,ms_per_frame,fps,commit\n";
    try {
        const float aspect = static_cast<float>(width) / static_cast<float>(height);
        for (const bool deformed : {false, true}) {
            const Scene scene = benchmark_scene(deformed);
            const std::string pose = deformed ? "deformed" : "rest";
            // Building the draw list alone (CPU, per frame in the studio).
            {
                DrawList list;
                const auto start = Clock::now();
                for (int f = 0; f < frames; ++f)
                    list = build_draw_list(scene);
                const double ms = 1e3 * seconds_since(start) / frames;
                csv << "build_draw_list," << pose << "," << scene.body.voxel_count() << ",0,0,0,"
                    << (threads ? threads : "auto") << "," << frames << "," << ms << "," << 1e3 / ms
                    << "," << commit << "\n";
            }
            for (int samples : {1, 4}) {
                OffscreenTarget target(width, height, samples);
                if (!deformed && samples == 1)
                    std::cerr << "bench_render: " << target.gl_renderer() << "\n";
                Renderer renderer;
                const DrawList list = build_draw_list(scene);
                Camera camera = named_view(NamedView::Iso, list.bounds, aspect);
                Image image;
                // Warm-up: shader compilation and first-use costs stay out of the figures.
                for (int f = 0; f < 3; ++f) {
                    renderer.draw(list, camera, width, height);
                    target.read_image(image);
                }
                // draw: a studio frame (draw list + draw + finish, the camera orbiting).
                auto start = Clock::now();
                for (int f = 0; f < frames; ++f) {
                    orbit(camera, 2.0f, 0.0f);
                    const DrawList frame_list = build_draw_list(scene);
                    renderer.draw(frame_list, camera, width, height);
                    glFinish();
                }
                double ms = 1e3 * seconds_since(start) / frames;
                csv << "frame_draw," << pose << "," << scene.body.voxel_count() << "," << width
                    << "," << height << "," << target.samples() << ","
                    << (threads ? threads : "auto") << "," << frames << "," << ms << "," << 1e3 / ms
                    << "," << commit << "\n";
                // draw + read back: what bhm render pays per video frame (before PNG/ffmpeg).
                start = Clock::now();
                for (int f = 0; f < frames; ++f) {
                    orbit(camera, 2.0f, 0.0f);
                    renderer.draw(list, camera, width, height);
                    target.read_image(image);
                }
                ms = 1e3 * seconds_since(start) / frames;
                csv << "frame_draw_readback," << pose << "," << scene.body.voxel_count() << ","
                    << width << "," << height << "," << target.samples() << ","
                    << (threads ? threads : "auto") << "," << frames << "," << ms << "," << 1e3 / ms
                    << "," << commit << "\n";
            }
        }
    } catch (const std::exception& e) {
        std::cerr << "bench_render: " << e.what() << "\n";
        return 1;
    }
    if (out_path.empty()) {
        std::cout << csv.str();
    } else {
        std::ofstream(out_path) << csv.str();
        std::cout << csv.str();
    }
    return 0;
}
