#pragma once
// A tiny line-segment font (seven-segment digits, a few signs, X Y Z) for labels drawn by the
// renderer itself: axis letters and colour-bar numbers, with no font file or texture.
#include <string>
#include <vector>

#include <glm/vec2.hpp>
#include <glm/vec4.hpp>

#include "render/draw_list.hpp"

namespace bhm::render {

//! Width of text of this height in pixels (unknown characters advance like a space).
float text_width_px(const std::string& text, float height_px);
//! Appends text as line pairs in pixel coordinates (z = 0); origin is the lower-left corner.
//! Supported: 0-9 . - + e E x X y Y z Z and space.
void add_text(std::vector<LineVertex>& lines, const std::string& text, glm::vec2 origin_px,
              float height_px, glm::vec4 color, float stroke_px = 1.5f);

}  // namespace bhm::render
