#include "app/gui/shell/headless_studio.hpp"

#include <glad/gl.h>
#include <malloc.h>

#include <utility>

#define GLFW_INCLUDE_NONE
#include <GLFW/glfw3.h>
#include <imgui.h>

#include "imgui_impl_opengl3.h"
#include "render/gl_check.hpp"
#include "render/offscreen.hpp"

namespace bhm::app::gui {

void keep_freed_memory_for_rendering() {
    mallopt(M_MMAP_THRESHOLD, 16 << 20);   // blocks below 16 MB come from the heap
    mallopt(M_TRIM_THRESHOLD, 128 << 20);  // and up to 128 MB of free heap is kept
}

struct HeadlessStudio::Gl {
    render::OffscreenTarget target;
    ImGuiContext* imgui = nullptr;
    bool backend = false;
    Gl(int w, int h) : target(w, h, 1) {}
};

HeadlessStudio::HeadlessStudio(Studio& studio, int width, int height)
    : studio_(studio),
      width_(width),
      height_(height),
      target_width_(width),
      target_height_(height) {
    keep_freed_memory_for_rendering();
    gl_ = std::make_unique<Gl>(width, height);
    gl_->target.bind();
    IMGUI_CHECKVERSION();
    gl_->imgui = ImGui::CreateContext();
    ImGuiIO& io = ImGui::GetIO();
    io.IniFilename = nullptr;  // the layout lives in our settings file, not imgui.ini
    io.LogFilename = nullptr;
    io.DisplaySize = ImVec2(static_cast<float>(width), static_cast<float>(height));
    io.BackendPlatformName = "bhm-headless";
    // Text fields understand the keys the GLFW backend maps (ImGui_ImplGlfw_Init's table);
    // scripts press the same codes.
    const std::pair<ImGuiKey_, int> keys[] = {
        {ImGuiKey_Tab, GLFW_KEY_TAB},           {ImGuiKey_LeftArrow, GLFW_KEY_LEFT},
        {ImGuiKey_RightArrow, GLFW_KEY_RIGHT},  {ImGuiKey_UpArrow, GLFW_KEY_UP},
        {ImGuiKey_DownArrow, GLFW_KEY_DOWN},    {ImGuiKey_PageUp, GLFW_KEY_PAGE_UP},
        {ImGuiKey_PageDown, GLFW_KEY_PAGE_DOWN}, {ImGuiKey_Home, GLFW_KEY_HOME},
        {ImGuiKey_End, GLFW_KEY_END},           {ImGuiKey_Insert, GLFW_KEY_INSERT},
        {ImGuiKey_Delete, GLFW_KEY_DELETE},     {ImGuiKey_Backspace, GLFW_KEY_BACKSPACE},
        {ImGuiKey_Space, GLFW_KEY_SPACE},       {ImGuiKey_Enter, GLFW_KEY_ENTER},
        {ImGuiKey_Escape, GLFW_KEY_ESCAPE},     {ImGuiKey_KeyPadEnter, GLFW_KEY_KP_ENTER},
        {ImGuiKey_A, GLFW_KEY_A},               {ImGuiKey_C, GLFW_KEY_C},
        {ImGuiKey_V, GLFW_KEY_V},               {ImGuiKey_X, GLFW_KEY_X},
        {ImGuiKey_Y, GLFW_KEY_Y},               {ImGuiKey_Z, GLFW_KEY_Z}};
    for (const auto& [imgui_key, glfw_key] : keys) io.KeyMap[imgui_key] = glfw_key;
    font_ = apply_studio_style(studio.settings.ui_scale);
    if (!ImGui_ImplOpenGL3_Init("#version 330 core")) {
        ImGui::DestroyContext(gl_->imgui);
        throw std::runtime_error("ImGui OpenGL3 backend failed to initialise on OSMesa");
    }
    gl_->backend = true;
    app_ = std::make_unique<StudioApp>(studio);
    // ImGui ignores the mouse over windows in the frames they appear in (they are laid out
    // hidden first): settle the layout so a script's first click lands.
    for (int i = 0; i < 3; ++i)
        frame();
}

HeadlessStudio::~HeadlessStudio() {
    app_.reset();
    if (gl_->backend) ImGui_ImplOpenGL3_Shutdown();
    if (gl_->imgui) ImGui::DestroyContext(gl_->imgui);
}

bool HeadlessStudio::set_display_size(int width, int height) {
    if (width < 1 || height < 1 || width > target_width_ || height > target_height_) return false;
    width_ = width;
    height_ = height;
    return true;
}

std::string HeadlessStudio::gl_renderer() const {
    return gl_->target.gl_renderer();
}

void HeadlessStudio::frame(double dt_s) {
    gl_->target.bind();
    ImGuiIO& io = ImGui::GetIO();
    io.DisplaySize = ImVec2(static_cast<float>(width_), static_cast<float>(height_));
    io.DisplayFramebufferScale = ImVec2(1.0f, 1.0f);
    io.DeltaTime = static_cast<float>(dt_s > 0.0 ? dt_s : 1.0 / 60.0);
    io.MousePos = ImVec2(input_.mouse.x, input_.mouse.y);
    for (int b = 0; b < 3; ++b) {
        const auto i = static_cast<std::size_t>(b);
        io.MouseDown[b] = input_.buttons[i] || input_.pressed_in_batch[i];
        input_.pressed_in_batch[i] = false;
    }
    io.MouseWheel = input_.wheel;
    input_.wheel = 0.0f;
    for (bool& down : io.KeysDown)
        down = false;
    input_.keys.deliver(io);
    io.KeyCtrl = io.KeyCtrl || input_.ctrl;
    io.KeyShift = io.KeyShift || input_.shift;
    if (input_.key > 0 && input_.key < IM_ARRAYSIZE(io.KeysDown)) io.KeysDown[input_.key] = true;
    for (const KeyChord& press : input_.key_presses)
        studio_.ui.key_presses.push_back(press);
    input_.key_presses.clear();

    ImGui_ImplOpenGL3_NewFrame();
    ImGui::NewFrame();
    app_->build_frame(dt_s);
    ImGui::Render();
    gl_->target.bind();
    glViewport(0, 0, width_, height_);
    const ImVec4 clear = ui_clear_color();
    glClearColor(clear.x, clear.y, clear.z, 1.0f);
    glClear(GL_COLOR_BUFFER_BIT | GL_DEPTH_BUFFER_BIT);
    ImGui_ImplOpenGL3_RenderDrawData(ImGui::GetDrawData());
    glFinish();  // the frame is done when this returns, as a window's swap would wait for it
    render::check_gl_error("drawing the studio frame");
}

render::Image HeadlessStudio::capture() {
    return gl_->target.read_image();
}

}  // namespace bhm::app::gui
