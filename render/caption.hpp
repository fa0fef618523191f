#pragma once
// Captions burnt into rendered frames (bhm render --caption): a built-in 5x7 dot font, white
// text on a translucent dark box in the top-left corner. Plain CPU drawing into an Image, so
// PNGs, videos and GIFs carry the same caption without a font file or GL text.
#include <string>
#include <vector>

#include "render/image.hpp"

namespace bhm::render {

//! Size of one font dot in pixels for an image of this height (about 1/240 of it, at least 1).
int caption_scale_for(int image_height_px);

//! Width and height in pixels of a line of text at this scale (glyph cell 6 x 8 dots).
int caption_text_width_px(const std::string& text, int scale);
int caption_line_height_px(int scale);

//! Draws the lines (digits, letters, space and . , : = - + ( ) / % _; others as '?', capitals as
//! small letters) on a box darkening what is behind it to 40%. Clipped to the image.
void draw_caption(Image& image, const std::vector<std::string>& lines, int scale);

}  // namespace bhm::render
