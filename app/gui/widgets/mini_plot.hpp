#pragma once
// Small plots drawn with ImDrawList (no ImPlot in ImGui 1.86): time series with a cursor that
// follows the replay clock (click or drag in the plot to scrub), and a scatter plot with
// hover. Axes fitted to the data with round ticks (plot_axes.hpp).
#include <optional>
#include <string>
#include <vector>

#include <imgui.h>

namespace bhm::app::gui {

struct PlotCurve {
    const std::vector<double>* y = nullptr;
    ImU32 color = IM_COL32(40, 40, 40, 255);
    const char* label = "";
    bool dots = false;  //!< a dot per sample (measurements) instead of a line
};

//! Curves over x (same length) in a size area at the cursor, a vertical cursor at cursor_x, and
//! the title and unit in the corner. Returns the x clicked or dragged to (seek), if any.
std::optional<double> draw_time_plot(const char* id, const std::vector<double>& x,
                                     const std::vector<PlotCurve>& curves, double cursor_x,
                                     const char* title, const char* unit, ImVec2 size);

struct ScatterPoint {
    double x = 0.0, y = 0.0;
    ImU32 color = IM_COL32(90, 90, 90, 255);
    float radius = 3.0f;
    bool ring = false;  //!< drawn with a ring around it (the champion)
};

//! A scatter plot (integer_x: ticks on whole numbers only); returns the index of the point clicked
//! (nearest within 8 px), if any, and sets *hovered to the one under the mouse. `screen`, when
//! given, gets each point's screen position (outside the plot area: a point it clips), so a
//! caller can record the points as widgets that scripts click.
std::optional<int> draw_scatter_plot(const char* id, const std::vector<ScatterPoint>& points,
                                     const char* x_label, const char* y_label, ImVec2 size,
                                     int* hovered, bool integer_x = false,
                                     std::vector<ImVec2>* screen = nullptr);

}  // namespace bhm::app::gui
