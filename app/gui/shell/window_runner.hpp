#pragma once
// The studio in a GLFW window (needs a display), and the headless runner for `--headless`.
#include <string>

#include "app/gui/studio.hpp"

namespace bhm::app::gui {

struct WindowOptions {
    int width = 0, height = 0;  //!< 0: from the settings
    int max_frames = 0;         //!< > 0: close after that many frames (smoke tests)
};

//! Runs the window until it is closed; returns the exit code. Saves the settings on the way out.
int run_window(Studio& studio, const WindowOptions& options);

struct HeadlessOptions {
    int width = 1280, height = 800;
    int frames = 3;          //!< at least this many frames in all (scripts may draw more)
    std::string screenshot;  //!< PNG of the last frame ("" = none)
    std::string script;      //!< JSON script file ("" = none)
};

//! Runs the UI off-screen; returns the exit code (1 with a one-line message on failure).
int run_headless(Studio& studio, const HeadlessOptions& options);

}  // namespace bhm::app::gui
