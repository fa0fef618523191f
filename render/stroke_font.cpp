#include "render/stroke_font.hpp"

#include <cctype>
#include <cstdint>
#include <utility>

namespace bhm::render {

namespace {

// Glyph cell: x in [0, 1], y in [0, 2]; drawn at height h, so one unit is h / 2 pixels.
constexpr float kAdvance = 0.75f;  // of the height

struct Segment {
    float x0, y0, x1, y1;
};

// Seven segments: a top, b upper right, c lower right, d bottom, e lower left, f upper left,
// g middle.
constexpr Segment kSeven[7] = {{0, 2, 1, 2}, {1, 2, 1, 1}, {1, 1, 1, 0}, {0, 0, 1, 0},
                               {0, 0, 0, 1}, {0, 1, 0, 2}, {0, 1, 1, 1}};
// Bit i lights kSeven[i] (a = bit 0).
constexpr std::uint8_t kDigitSegments[10] = {0x3F, 0x06, 0x5B, 0x4F, 0x66,
                                             0x6D, 0x7D, 0x07, 0x7F, 0x6F};

std::vector<Segment> glyph(char c) {
    std::vector<Segment> segments;
    auto seven = [&](std::uint8_t bits) {
        for (int i = 0; i < 7; ++i)
            if (bits & (1u << i)) segments.push_back(kSeven[i]);
    };
    if (c == '1') {
        // Centred, unlike the seven-segment right-hand bar, so numbers read evenly spaced.
        segments.push_back({0.5f, 0.0f, 0.5f, 2.0f});
        segments.push_back({0.5f, 2.0f, 0.25f, 1.7f});
        return segments;
    }
    if (c >= '0' && c <= '9') {
        seven(kDigitSegments[c - '0']);
        return segments;
    }
    switch (std::toupper(static_cast<unsigned char>(c))) {
        case '-':
            seven(0x40);
            break;
        case '+':
            seven(0x40);
            segments.push_back({0.5f, 0.5f, 0.5f, 1.5f});
            break;
        case '.':
            segments.push_back({0.4f, 0.0f, 0.6f, 0.0f});
            break;
        case 'E':
            seven(0x79);
            break;
        case 'X':
            segments.push_back({0, 0, 1, 2});
            segments.push_back({0, 2, 1, 0});
            break;
        case 'Y':
            segments.push_back({0, 2, 0.5f, 1});
            segments.push_back({1, 2, 0.5f, 1});
            segments.push_back({0.5f, 1, 0.5f, 0});
            break;
        case 'Z':
            segments.push_back({0, 2, 1, 2});
            segments.push_back({1, 2, 0, 0});
            segments.push_back({0, 0, 1, 0});
            break;
        default:
            break;
    }
    return segments;
}

}  // namespace

float text_width_px(const std::string& text, float height_px) {
    if (text.empty()) return 0.0f;
    // The last glyph is one unit (h / 2) wide, the others advance by kAdvance * h.
    return (static_cast<float>(text.size() - 1) * kAdvance + 0.5f) * height_px;
}

void add_text(std::vector<LineVertex>& lines, const std::string& text, glm::vec2 origin_px,
              float height_px, glm::vec4 color, float stroke_px) {
    const float unit = 0.5f * height_px;
    glm::vec2 pen = origin_px;
    for (char c : text) {
        for (const Segment& s : glyph(c)) {
            lines.push_back({{pen.x + s.x0 * unit, pen.y + s.y0 * unit, 0.0f}, color, stroke_px});
            lines.push_back({{pen.x + s.x1 * unit, pen.y + s.y1 * unit, 0.0f}, color, stroke_px});
        }
        pen.x += kAdvance * height_px;
    }
}

}  // namespace bhm::render
