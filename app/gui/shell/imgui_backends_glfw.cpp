// Dear ImGui's GLFW platform backend, compiled from libimgui-dev's shipped source so it matches
// the headers exactly (app/CMakeLists.txt checks the folder exists at configure time).
#include "imgui_impl_glfw.cpp"
