#include "app/gui/shell/window_runner.hpp"

#include <glad/gl.h>

#define GLFW_INCLUDE_NONE  // GL comes from glad only
#include <GLFW/glfw3.h>

#include <chrono>
#include <iostream>

#include <imgui.h>

#include "app/gui/actions/key_bindings.hpp"
#include "app/gui/actions/unsaved_guard.hpp"
#include "app/gui/shell/headless_studio.hpp"
#include "app/gui/shell/key_event_queue.hpp"
#include "app/gui/shell/redraw_gate.hpp"
#include "app/gui/shell/script.hpp"
#include "app/gui/studio_app.hpp"
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

// What the GLFW callbacks reach through the window's user pointer.
struct WindowContext {
    Studio& studio;
    RedrawGate gate;
    KeyEventQueue keys;  //!< ImGui's keys and characters, handed over a frame at a time
};

WindowContext* context_of(GLFWwindow* window) {
    return static_cast<WindowContext*>(glfwGetWindowUserPointer(window));
}

// The window's input. ImGui's backend installs no callbacks of its own (its key callback would
// set io.KeysDown at once, losing a press released before the frame): keys and characters go
// through the KeyEventQueue, the mouse, scroll, focus and cursor-enter events on to the backend.
// Each one is a reason to draw.

// Records each press with the modifiers of that moment: a press released before the next frame
// still reaches the key bindings. Repeats of a held key are recorded too, marked (a held Down
// moves on in the file dialog).
void on_key(GLFWwindow* window, int key, int /*scancode*/, int action, int mods) {
    WindowContext* c = context_of(window);
    if (!c) return;
    c->gate.input();
    c->keys.key(key, action, mods);
    if (const auto chord = key_event_chord(key, action, mods))
        c->studio.ui.key_presses.push_back(*chord);
}
void on_char(GLFWwindow* window, unsigned int codepoint) {
    if (WindowContext* c = context_of(window)) {
        c->gate.input();
        c->keys.character(codepoint);
    }
}
void on_button(GLFWwindow* window, int button, int action, int mods) {
    ImGui_ImplGlfw_MouseButtonCallback(window, button, action, mods);
    if (WindowContext* c = context_of(window)) c->gate.input();
}
void on_scroll(GLFWwindow* window, double x, double y) {
    ImGui_ImplGlfw_ScrollCallback(window, x, y);
    if (WindowContext* c = context_of(window)) c->gate.input();
}
void on_focus(GLFWwindow* window, int focused) {
    ImGui_ImplGlfw_WindowFocusCallback(window, focused);
    if (WindowContext* c = context_of(window)) c->gate.input();
}
void on_cursor_enter(GLFWwindow* window, int entered) {
    ImGui_ImplGlfw_CursorEnterCallback(window, entered);
}

double seconds(std::chrono::steady_clock::time_point t) {
    return std::chrono::duration<double>(t.time_since_epoch()).count();
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
    WindowContext window_context{studio, {}, {}};
    RedrawGate& gate = window_context.gate;
    glfwSetWindowUserPointer(window.handle(), &window_context);
    ImGui_ImplGlfw_InitForOpenGL(window.handle(), false);  // the callbacks are ours (above)
    glfwSetKeyCallback(window.handle(), on_key);
    glfwSetMouseButtonCallback(window.handle(), on_button);
    glfwSetScrollCallback(window.handle(), on_scroll);
    glfwSetCharCallback(window.handle(), on_char);
    glfwSetWindowFocusCallback(window.handle(), on_focus);
    glfwSetCursorEnterCallback(window.handle(), on_cursor_enter);
    ImGui_ImplOpenGL3_Init("#version 330 core");
    int exit_code = 0;
    {
        StudioApp app(studio);
        auto last = std::chrono::steady_clock::now();
        double fps_accumulator = 0.0;
        int fps_frames = 0;
        std::string shown_title;
        double cursor_x = -1.0, cursor_y = -1.0;
        int window_w = 0, window_h = 0;
        for (int frame = 0; !studio.ui.quit_requested; ++frame) {
            if (options.max_frames > 0 && frame >= options.max_frames) break;
            // The window's close button asks like Ctrl+Q (unsaved edits, a running run); the
            // window stays open while the question is shown.
            if (window.should_close() && !window_close_requested(studio)) {
                glfwSetWindowShouldClose(window.handle(), GLFW_FALSE);
                gate.input();
            }
            // Nothing moves by itself: wait for input (saves the cores for evolution), waking 4
            // times a second to pick up new generations; the gate says whether to draw.
            // Keys still queued for ImGui (one a frame) are drawn without waiting for input.
            if (window_context.keys.pending()) gate.input();
            if (needs_animation(studio) || frame < 3 || window_context.keys.pending())
                window.poll_events();
            else
                glfwWaitEventsTimeout(0.25);
            // Pointer moves and resizes have no callback that ImGui's backend chains: compare.
            double x = 0.0, y = 0.0;
            int w = 0, h = 0;
            glfwGetCursorPos(window.handle(), &x, &y);
            glfwGetWindowSize(window.handle(), &w, &h);
            if (x != cursor_x || y != cursor_y || w != window_w || h != window_h) gate.input();
            cursor_x = x, cursor_y = y, window_w = w, window_h = h;
            if (!gate.should_draw(studio, seconds(std::chrono::steady_clock::now()))) {
                --frame;  // frames count the ones drawn
                continue;
            }
            const auto now = std::chrono::steady_clock::now();
            const double dt = std::chrono::duration<double>(now - last).count();
            last = now;
            fps_accumulator += dt;
            if (++fps_frames == 30) {
                studio.ui.fps = fps_frames / fps_accumulator;
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
            window_context.keys.deliver(io);
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
    while (studio.ui.frame < options.frames)
        session.frame();
    if (!options.screenshot.empty()) render::write_png(options.screenshot, session.capture());
    save_settings_quietly(studio);
    return 0;
}

}  // namespace bhm::app::gui
