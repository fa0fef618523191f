#include "render/image.hpp"

#include <stb_image.h>
#include <stb_image_write.h>

#include <algorithm>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <stdexcept>
#include <system_error>

#include "engine/io/atomic_file.hpp"

namespace bhm::render {

void write_png(const std::string& path, const Image& image) {
    if (image.width <= 0 || image.height <= 0)
        throw std::runtime_error(path + ": cannot write an empty image");
    std::vector<std::uint8_t> rgb(static_cast<std::size_t>(image.width) * image.height * 3);
    for (std::size_t i = 0, n = rgb.size() / 3; i < n; ++i)
        for (std::size_t c = 0; c < 3; ++c)
            rgb[3 * i + c] = image.rgba[4 * i + c];
    // Encoded in memory, then written through the checked atomic writer: stb's own file writer
    // ignores write and close errors (a full disk left a 0-byte PNG behind a "wrote").
    std::string png;
    const auto append = [](void* context, void* data, int size) {
        static_cast<std::string*>(context)->append(static_cast<const char*>(data),
                                                   static_cast<std::size_t>(size));
    };
    if (!stbi_write_png_to_func(append, &png, image.width, image.height, 3, rgb.data(),
                                image.width * 3))
        throw std::runtime_error(path + ": cannot encode the PNG");
    engine::write_file_atomically(path, png);
}

Image read_png(const std::string& path) {
    int w = 0, h = 0, channels = 0;
    unsigned char* data = stbi_load(path.c_str(), &w, &h, &channels, 4);
    if (!data) {
        const char* reason = stbi_failure_reason();
        throw std::runtime_error(path +
                                 ": cannot read PNG: " + (reason ? reason : "unknown error"));
    }
    Image image(w, h);
    std::copy(data, data + static_cast<std::size_t>(w) * h * 4, image.rgba.begin());
    stbi_image_free(data);
    return image;
}

ImageDifference compare_images(const Image& a, const Image& b, int threshold) {
    ImageDifference result;
    if (a.width != b.width || a.height != b.height) {
        result.same_size = false;
        result.mean_abs_diff = 1.0;
        result.fraction_over = 1.0;
        result.max_diff = 255;
        return result;
    }
    result.diff = Image(a.width, a.height);
    const std::size_t pixels = static_cast<std::size_t>(a.width) * a.height;
    std::uint64_t total = 0, over = 0;
    for (std::size_t i = 0; i < pixels; ++i) {
        int largest = 0;
        for (std::size_t c = 0; c < 3; ++c) {
            const int d = std::abs(int(a.rgba[4 * i + c]) - int(b.rgba[4 * i + c]));
            total += static_cast<std::uint64_t>(d);
            largest = std::max(largest, d);
            result.diff.rgba[4 * i + c] =
                static_cast<std::uint8_t>(std::min(255, d == 0 ? 40 : 4 * d + 60));
        }
        result.diff.rgba[4 * i + 3] = 255;
        result.max_diff = std::max(result.max_diff, largest);
        over += largest > threshold;
    }
    if (pixels > 0) {
        result.mean_abs_diff =
            static_cast<double>(total) / (3.0 * 255.0 * static_cast<double>(pixels));
        result.fraction_over = static_cast<double>(over) / static_cast<double>(pixels);
    }
    return result;
}

}  // namespace bhm::render
