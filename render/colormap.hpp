#pragma once
// Colour maps for per-voxel scalars (displacement, strain, actuation phase).
#include <algorithm>
#include <cmath>
#include <cstdint>
#include <optional>
#include <string>

#include <glm/vec4.hpp>

namespace bhm::render {

enum class ColorMapName : std::uint8_t {
    Sequential,  //!< dark blue -> teal -> yellow: magnitudes (displacement)
    Diverging,   //!< blue -> white -> red: signed values around zero (strain)
    Cyclic,      //!< hue wheel that wraps: angles (actuation phase)
    Axes,        //!< three flat colours, x red, y green, z blue: a lattice axis 0, 1, 2 over [0, 2]
};

struct ScalarRange {
    float min = 0.0f;
    float max = 1.0f;
    //! Position of value in the range, clamped to [0, 1]; 0.5 for an empty, infinite or NaN
    //! range and for a NaN value.
    float normalize(float value) const;
};

//! The largest magnitude a colour scale shows (10^37): a scale [-m, m] or [0, m] keeps a finite
//! span and middle in float, whose largest value is 3.4e38.
inline constexpr double kMaxScaleMagnitude = 1e37;

//! The colour scale of a field, from its values' magnitudes, found in double. Non-finite values
//! (a diverged voxel's inf or NaN) are left out: they get the scale's end colour, not its range.
//! A replay holding 3.4e38 made the range, found in float, "-inf to inf" (issue 41).
class ScalarExtent {
  public:
    void add(double value) {
        if (std::isfinite(value)) largest_ = std::max(largest_, std::fabs(value));
    }
    //! The largest finite magnitude added; 0 when none.
    double largest() const { return largest_; }
    //! [0, m] or, symmetric, [-m, m]: m the largest magnitude clamped to kMaxScaleMagnitude, or
    //! `fallback` when no value above zero was added.
    ScalarRange range(bool symmetric, double fallback) const;

  private:
    double largest_ = 0.0;
};

//! Colour (alpha 1) at t in [0, 1]; t outside is clamped (Cyclic wraps); NaN and infinities give
//! the colour at 0.
glm::vec4 sample_color_map(ColorMapName map, float t);

std::optional<ColorMapName> parse_color_map(const std::string& name);
const char* color_map_name(ColorMapName map);

}  // namespace bhm::render
