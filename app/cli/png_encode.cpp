// libpng in memory (png_encode.hpp); BHM_WITH_PNG is set on this file alone by app/CMakeLists.txt.
#include "app/cli/png_encode.hpp"

#include <stdexcept>

#include "evo/experiment/experiment_io.hpp"

#ifdef BHM_WITH_PNG
#include <png.h>
#endif

namespace bhm::app {

bool png_available() {
#ifdef BHM_WITH_PNG
    return true;
#else
    return false;
#endif
}

std::string encode_rgb_png(int width, int height, const std::vector<std::uint8_t>& rgb) {
    if (width <= 0 || height <= 0 ||
        rgb.size() != static_cast<std::size_t>(width) * static_cast<std::size_t>(height) * 3)
        throw std::runtime_error("PNG: the pixels do not match the image size");
#ifndef BHM_WITH_PNG
    throw std::runtime_error("bhm was built without libpng, so it cannot write PNG");
#else
    std::string out;
    png_structp png = png_create_write_struct(PNG_LIBPNG_VER_STRING, nullptr, nullptr, nullptr);
    png_infop info = png ? png_create_info_struct(png) : nullptr;
    if (!png || !info) {
        png_destroy_write_struct(&png, nullptr);
        throw std::runtime_error("cannot start the PNG encoder");
    }
    if (setjmp(png_jmpbuf(png))) {
        png_destroy_write_struct(&png, &info);
        throw std::runtime_error("cannot encode the PNG");
    }
    png_set_write_fn(
        png, &out,
        [](png_structp p, png_bytep data, png_size_t n) {
            static_cast<std::string*>(png_get_io_ptr(p))->append(reinterpret_cast<char*>(data), n);
        },
        nullptr);
    png_set_IHDR(png, info, static_cast<png_uint_32>(width), static_cast<png_uint_32>(height), 8,
                 PNG_COLOR_TYPE_RGB, PNG_INTERLACE_NONE, PNG_COMPRESSION_TYPE_DEFAULT,
                 PNG_FILTER_TYPE_DEFAULT);
    png_write_info(png, info);
    for (int y = 0; y < height; ++y)
        png_write_row(png, const_cast<png_bytep>(&rgb[static_cast<std::size_t>(y) * width * 3]));
    png_write_end(png, nullptr);
    png_destroy_write_struct(&png, &info);
    return out;
#endif
}

void write_rgb_png(const std::string& path, int width, int height,
                   const std::vector<std::uint8_t>& rgb) {
    std::string png;
    try {
        png = encode_rgb_png(width, height, rgb);
    } catch (const std::runtime_error& e) {
        throw std::runtime_error(path + ": " + e.what());
    }
    evo::write_file_atomically(path, png);
}

}  // namespace bhm::app
