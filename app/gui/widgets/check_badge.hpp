#pragma once
// The badge of a body checked in CalculiX inside the evolution loop (evolution.verify;
// docs/studio.md, "CalculiX in the loop"): "FEM ok 4 %", "FEM differs 23 %" or "FEM n/a", in
// green, red or grey, with the verdict and the generation on hover. The same badge in the
// Population and Champions tables and over the 3D view; unchecked bodies have none.
#include <string>

#include <imgui.h>

#include "app/gui/studio.hpp"
#include "evo/run/loop_check.hpp"

namespace bhm::app::gui {

struct CheckBadge {
    std::string text;     //!< "FEM ok 4 %"
    ImVec4 color;         //!< green agrees, red differs, grey not compared
    std::string tooltip;  //!< the verdict line, then where the body was picked
};

//! The badge of one check: plain data, so tests read it without drawing.
CheckBadge check_badge(const evo::LoopCheck& check);

//! Draws the badge as a table cell's text, recorded as the widget `name`, its tooltip on hover;
//! nothing for a null check.
void draw_check_badge(Studio& studio, const evo::LoopCheck* check, const std::string& name);

}  // namespace bhm::app::gui
