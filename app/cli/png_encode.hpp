#pragma once
// PNG encoding for the CLI's plots (bhm calibrate's track plot, bhm robustness's heatmap): 8-bit
// RGB rows encoded in memory with libpng (Debian's libpng-dev, optional), so that the caller
// writes the bytes atomically (evo::write_file_atomically). No display and no GL.
#include <cstdint>
#include <string>
#include <vector>

namespace bhm::app {

//! False where bhm was built without libpng: encode_rgb_png then throws.
bool png_available();

//! rgb: height rows top to bottom, width x 3 bytes each. Throws std::runtime_error (without a
//! path: the caller names the file).
std::string encode_rgb_png(int width, int height, const std::vector<std::uint8_t>& rgb);

//! Encodes and writes `path` atomically; errors name the path.
void write_rgb_png(const std::string& path, int width, int height,
                   const std::vector<std::uint8_t>& rgb);

}  // namespace bhm::app
