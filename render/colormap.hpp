#pragma once
// Colour maps for per-voxel scalars (displacement, strain, actuation phase).
#include <cstdint>
#include <optional>
#include <string>

#include <glm/vec4.hpp>

namespace bhm::render {

enum class ColorMapName : std::uint8_t {
    Sequential,  //!< dark blue -> teal -> yellow: magnitudes (displacement)
    Diverging,   //!< blue -> white -> red: signed values around zero (strain)
    Cyclic,      //!< hue wheel that wraps: angles (actuation phase)
};

struct ScalarRange {
    float min = 0.0f;
    float max = 1.0f;
    //! Position of value in the range, clamped to [0, 1]; 0.5 for an empty, infinite or NaN
    //! range and for a NaN value.
    float normalize(float value) const;
};

//! Colour (alpha 1) at t in [0, 1]; t outside is clamped (Cyclic wraps); NaN and infinities give
//! the colour at 0.
glm::vec4 sample_color_map(ColorMapName map, float t);

std::optional<ColorMapName> parse_color_map(const std::string& name);
const char* color_map_name(ColorMapName map);

}  // namespace bhm::render
