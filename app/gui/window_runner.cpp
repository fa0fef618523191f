#include "app/gui/window_runner.hpp"

#include <glad/gl.h>

#define GLFW_INCLUDE_NONE  // GL comes from glad only
#include <GLFW/glfw3.h>

#include <chrono>
#include <iostream>

#include <imgui.h>

#include "app/gui/headless_session.hpp"
#include "app/gui/script.hpp"
#include "app/gui/studio_app.hpp"
#include "app/gui/unsaved_guard.hpp"
#include "imgui_impl_glfw.h"
#include "imgui_impl_opengl3.h"
#include "render/window.hpp"

namespace bhm::app::gui {

namespace {

void save_settings_quietly(Studio& studio) {
    if (studio.settings_path.empty()) return;
    store_view_settings(studio);
    try {
        save_settings(studio.settings_path, studio.settings);
    } catch (const std::exception& e) {
        std::cerr << "bhm studio: " << e.what() << "\n";
    }
}

// Something moves on screen: draw continuously; otherwise wait for input (saves the cores for
// evolution) but wake up 4 times a second to pick up new generations.
bool animating(const Studio& s) {
    return s.clock.playing || run_is_live(s.evolution.phase()) || s.simulator.busy() ||
           s.exports.frame_job.active || s.view.dragging;
}

}  // namespace

int run_window(Studio& studio, const WindowOptions& options) {
    const int width = options.width > 0 ? options.width : studio.settings.window_width;
    const int height = options.height > 0 ? options.height : studio.settings.window_height;
    keep_freed_memory_for_rendering();
    render::Window window(width, height, "BHM Studio", 1);
    window.set_vsync(true);
    IMGUI_CHECKVERSION();
    ImGuiContext* context = ImGui::CreateContext();
    ImGuiIO& io = ImGui::GetIO();
    io.IniFilename = nullptr;
    apply_studio_style(studio.settings.ui_scale);
    ImGui_ImplGlfw_InitForOpenGL(window.handle(), true);
    ImGui_ImplOpenGL3_Init("#version 330 core");
    int exit_code = 0;
    {
        StudioApp app(studio);
        auto last = std::chrono::steady_clock::now();
        double fps_accumulator = 0.0;
        int fps_frames = 0;
        std::string shown_title;
        for (int frame = 0; !studio.quit_requested; ++frame) {
            if (options.max_frames > 0 && frame >= options.max_frames) break;
            // The window's close button asks like Ctrl+Q (unsaved edits, a running run); the
            // window stays open while the question is shown.
            if (window.should_close() && !window_close_requested(studio))
                glfwSetWindowShouldClose(window.handle(), GLFW_FALSE);
            if (animating(studio) || frame < 3)
                window.poll_events();
            else
                glfwWaitEventsTimeout(0.25);
            const auto now = std::chrono::steady_clock::now();
            const double dt = std::chrono::duration<double>(now - last).count();
            last = now;
            fps_accumulator += dt;
            if (++fps_frames == 30) {
                studio.fps = fps_frames / fps_accumulator;
                fps_accumulator = 0.0;
                fps_frames = 0;
            }
            // The title names the document and marks unsaved changes.
            const std::string title = "BHM Studio - " + document_label(studio.document) +
                                      (studio.document.dirty() ? " *" : "");
            if (title != shown_title) {
                glfwSetWindowTitle(window.handle(), title.c_str());
                shown_title = title;
            }
            ImGui_ImplOpenGL3_NewFrame();
            ImGui_ImplGlfw_NewFrame();
            ImGui::NewFrame();
            app.build_frame(std::min(dt, 0.25));
            ImGui::Render();
            window.bind();
            glViewport(0, 0, window.framebuffer_width(), window.framebuffer_height());
            const ImVec4 clear = ui_clear_color();
            glClearColor(clear.x, clear.y, clear.z, 1.0f);
            glClear(GL_COLOR_BUFFER_BIT);
            ImGui_ImplOpenGL3_RenderDrawData(ImGui::GetDrawData());
            window.swap_buffers();
        }
        glfwGetWindowSize(window.handle(), &studio.settings.window_width,
                          &studio.settings.window_height);
    }
    ImGui_ImplOpenGL3_Shutdown();
    ImGui_ImplGlfw_Shutdown();
    ImGui::DestroyContext(context);
    save_settings_quietly(studio);
    return exit_code;
}

int run_headless(Studio& studio, const HeadlessOptions& options) {
    nlohmann::json steps = nlohmann::json::array();
    try {
        if (!options.script.empty()) steps = load_script(options.script);  // names the file
    } catch (const ScriptError& e) {
        std::cerr << "bhm studio: " << e.what() << "\n";
        return 1;
    }
    HeadlessStudio session(studio, options.width, options.height);
    try {
        run_script(session, steps);
    } catch (const ScriptError& e) {
        std::cerr << "bhm studio: " << options.script << ": " << e.what() << "\n";
        return 1;
    }
    while (studio.frame < options.frames)
        session.frame();
    if (!options.screenshot.empty()) render::write_png(options.screenshot, session.capture());
    save_settings_quietly(studio);
    return 0;
}

}  // namespace bhm::app::gui
