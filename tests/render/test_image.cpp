// PNG files and image comparison (the golden tests depend on both being right).
#include <doctest/doctest.h>

#include <filesystem>
#include <fstream>

#include "render/image.hpp"

using namespace bhm::render;

namespace {
std::string temp_path(const std::string& name) {
    const auto dir = std::filesystem::path(BHM_BINARY_DIR) / "test-render-tmp";
    std::filesystem::create_directories(dir);
    return (dir / name).string();
}

Image gradient(int w, int h) {
    Image image(w, h);
    for (int y = 0; y < h; ++y)
        for (int x = 0; x < w; ++x) {
            auto* p = image.pixel(x, y);
            p[0] = static_cast<std::uint8_t>(x * 255 / (w - 1));
            p[1] = static_cast<std::uint8_t>(y * 255 / (h - 1));
            p[2] = 77;
            p[3] = 255;
        }
    return image;
}
}  // namespace

TEST_CASE("PNG round trip keeps every pixel, the write leaves no temp file") {
    const Image image = gradient(33, 17);
    const std::string path = temp_path("roundtrip.png");
    write_png(path, image);
    CHECK_FALSE(std::filesystem::exists(path + ".tmp"));
    const Image back = read_png(path);
    CHECK(back.width == 33);
    CHECK(back.height == 17);
    CHECK(back.rgba == image.rgba);
}

TEST_CASE("PNG errors name the file") {
    CHECK_THROWS_WITH(read_png(temp_path("missing.png")),
                      doctest::Contains("missing.png: cannot read PNG"));
    const std::string junk = temp_path("junk.png");
    std::ofstream(junk) << "not a png";
    CHECK_THROWS_WITH(read_png(junk), doctest::Contains("junk.png"));
    CHECK_THROWS_WITH(write_png(temp_path("no/such/dir/x.png"), gradient(4, 4)),
                      doctest::Contains("x.png"));
}

TEST_CASE("an existing PNG survives a failed overwrite") {
    const std::string path = temp_path("keep.png");
    write_png(path, gradient(8, 8));
    CHECK_THROWS(write_png(path, Image()));  // empty image: refused before touching the file
    CHECK(read_png(path).width == 8);
}

TEST_CASE("image comparison: mean difference, share of pixels over the threshold, maximum") {
    Image a = gradient(10, 10);
    Image b = a;
    auto same = compare_images(a, b);
    CHECK(same.mean_abs_diff == 0.0);
    CHECK(same.fraction_over == 0.0);
    CHECK(same.max_diff == 0);
    b.pixel(3, 4)[0] =
        static_cast<std::uint8_t>(b.pixel(3, 4)[0] + 30);  // one pixel, one channel, +30
    b.pixel(5, 5)[2] = static_cast<std::uint8_t>(b.pixel(5, 5)[2] + 10);  // below the threshold
    const auto d = compare_images(a, b, 16);
    CHECK(d.max_diff == 30);
    CHECK(d.fraction_over == doctest::Approx(1.0 / 100));
    CHECK(d.mean_abs_diff == doctest::Approx(40.0 / (3 * 255.0 * 100)));
    CHECK(d.diff.width == 10);
    CHECK_FALSE(compare_images(a, gradient(10, 11)).same_size);
}
