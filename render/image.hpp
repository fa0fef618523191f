#pragma once
// RGBA8 images, PNG files and pixel comparisons (for golden-image tests and bhm render).
#include <cstdint>
#include <string>
#include <vector>

namespace bhm::render {

//! Rows top to bottom, 4 bytes per pixel (RGBA).
struct Image {
    int width = 0, height = 0;
    std::vector<std::uint8_t> rgba;

    Image() = default;
    Image(int w, int h) : width(w), height(h), rgba(static_cast<std::size_t>(w) * h * 4, 0) {}
    std::uint8_t* pixel(int x, int y) {
        return &rgba[(static_cast<std::size_t>(y) * width + x) * 4];
    }
    const std::uint8_t* pixel(int x, int y) const {
        return &rgba[(static_cast<std::size_t>(y) * width + x) * 4];
    }
};

//! Writes an RGB PNG atomically (path.tmp, then rename). Throws std::runtime_error naming path.
void write_png(const std::string& path, const Image& image);
//! Reads any PNG as RGBA. Throws std::runtime_error naming path and the decoder's reason.
Image read_png(const std::string& path);

struct ImageDifference {
    double mean_abs_diff = 0.0;  //!< over R, G, B of all pixels, in [0, 1]
    double fraction_over = 0.0;  //!< pixels whose largest channel difference > threshold
    int max_diff = 0;            //!< largest channel difference, 0..255
    Image diff;                  //!< per-pixel |a - b| x 4, grey where equal
    bool same_size = true;
};
//! Compares RGB channels of two images of the same size (sizes differ: same_size = false and
//! every figure at its worst).
ImageDifference compare_images(const Image& a, const Image& b, int threshold = 16);

}  // namespace bhm::render
