// Dear ImGui's OpenGL3 renderer backend, compiled from libimgui-dev's shipped source against our
// glad loader (the prebuilt one in libimgui.a loads its own GL and fails on OSMesa). Our object
// wins over the archive member, so there are no duplicate symbols. See /work/shared/toolchain.md.
#include <glad/gl.h>
#define IMGUI_IMPL_OPENGL_LOADER_CUSTOM
#include "imgui_impl_opengl3.cpp"
