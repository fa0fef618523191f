#pragma once
// An 8-bit RGB image to draw the CLI's plots on (bhm calibrate's track plot, bhm robustness's
// heatmap) before png_encode.hpp encodes it: rows top to bottom, white at first; drawing outside
// the image is clipped.
#include <array>
#include <cstddef>
#include <cstdint>
#include <cstdlib>
#include <vector>

namespace bhm::app {

using Rgb = std::array<std::uint8_t, 3>;

struct RgbCanvas {
    int width, height;
    std::vector<std::uint8_t> rgb;
    RgbCanvas(int w, int h) : width(w), height(h), rgb(static_cast<std::size_t>(w) * h * 3, 255) {}
    void put(int x, int y, Rgb c) {
        if (x < 0 || y < 0 || x >= width || y >= height) return;
        auto* p = &rgb[(static_cast<std::size_t>(y) * width + x) * 3];
        p[0] = c[0], p[1] = c[1], p[2] = c[2];
    }
    void fill(int x0, int y0, int w, int h, Rgb c) {
        for (int y = y0; y < y0 + h; ++y)
            for (int x = x0; x < x0 + w; ++x)
                put(x, y, c);
    }
    // Bresenham, 2 pixels thick.
    void line(int x0, int y0, int x1, int y1, Rgb c) {
        const int dx = std::abs(x1 - x0), dy = -std::abs(y1 - y0);
        const int sx = x0 < x1 ? 1 : -1, sy = y0 < y1 ? 1 : -1;
        int err = dx + dy;
        for (;;) {
            put(x0, y0, c), put(x0, y0 + 1, c);
            if (x0 == x1 && y0 == y1) break;
            const int e2 = 2 * err;
            if (e2 >= dy) err += dy, x0 += sx;
            if (e2 <= dx) err += dx, y0 += sy;
        }
    }
    void dot(int x, int y, Rgb c) { fill(x - 2, y - 2, 5, 5, c); }
};

}  // namespace bhm::app
