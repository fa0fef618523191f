// Captions burnt into frames: dots where the glyph has them, a darkened box, nothing outside it.
#include <doctest/doctest.h>

#include "render/caption.hpp"

using namespace bhm::render;

namespace {

Image grey(int w, int h) {
    Image image(w, h);
    for (auto& v : image.rgba)
        v = 100;
    return image;
}

int white_pixels(const Image& image) {
    int n = 0;
    for (int y = 0; y < image.height; ++y)
        for (int x = 0; x < image.width; ++x)
            n += image.pixel(x, y)[0] == 255 ? 1 : 0;
    return n;
}

}  // namespace

TEST_CASE("a caption's glyphs have their dots: '1' is 10 dots, '8' is 17, at scale^2 pixels") {
    for (int scale : {1, 3}) {
        Image one = grey(200, 100);
        draw_caption(one, {"1"}, scale);
        CHECK(white_pixels(one) == 10 * scale * scale);
        Image eight = grey(200, 100);
        draw_caption(eight, {"8"}, scale);
        CHECK(white_pixels(eight) == 17 * scale * scale);
    }
    // Capitals are drawn as small letters; unknown characters as '?'.
    Image upper = grey(200, 100), lower = grey(200, 100), odd = grey(200, 100),
          question = grey(200, 100);
    draw_caption(upper, {"BEND"}, 2);
    draw_caption(lower, {"bend"}, 2);
    draw_caption(odd, {"#"}, 2);
    draw_caption(question, {"?"}, 2);
    CHECK(upper.rgba == lower.rgba);
    CHECK(odd.rgba == question.rgba);
}

TEST_CASE("the caption box darkens the top-left corner only and grows with the text") {
    Image image = grey(320, 200);
    const int scale = 2;
    draw_caption(image, {"t = 1.000 s", "fitness 0.250 (com_final_3d)", "bend 12.5 deg"}, scale);
    const int width = caption_text_width_px("fitness 0.250 (com_final_3d)", scale);
    CHECK(width == 28 * 6 * scale);
    int darkened = 0, touched_outside = 0;
    for (int y = 0; y < image.height; ++y)
        for (int x = 0; x < image.width; ++x) {
            const auto v = image.pixel(x, y)[0];
            const bool inside =
                x < width + 6 * scale && y < 3 * caption_line_height_px(scale) + 6 * scale;
            if (v == 40) ++darkened;
            if (!inside && v != 100) ++touched_outside;
        }
    CHECK(touched_outside == 0);
    CHECK(darkened > width * caption_line_height_px(scale));
    CHECK(white_pixels(image) > 0);
    // A caption wider than the image is clipped, not written out of bounds.
    Image small = grey(20, 10);
    draw_caption(small, {"a long caption that does not fit"}, 3);
    CHECK(small.rgba.size() == 20u * 10u * 4u);
    CHECK(caption_scale_for(720) == 3);
    CHECK(caption_scale_for(100) == 1);
}
