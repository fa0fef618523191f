#include "app/gui/widgets/mini_plot.hpp"

#include <algorithm>
#include <cmath>

#include "app/gui/widgets/plot_axes.hpp"
#include "app/gui/widgets/ui_widgets.hpp"

namespace bhm::app::gui {

namespace {

constexpr ImU32 kGrid = IM_COL32(0, 0, 0, 28);
constexpr ImU32 kAxis = IM_COL32(60, 60, 60, 255);
constexpr ImU32 kText = IM_COL32(40, 40, 40, 255);
constexpr ImU32 kCursor = IM_COL32(214, 69, 56, 255);

struct Frame {
    ImVec2 lo, hi;
    AxisRange xr, yr;
    float px(double x) const { return lo.x + float((x - xr.min) / xr.span()) * (hi.x - lo.x); }
    float py(double y) const { return hi.y - float((y - yr.min) / yr.span()) * (hi.y - lo.y); }
    double x_at(float px_) const { return xr.min + (px_ - lo.x) / (hi.x - lo.x) * xr.span(); }
};

// Background, grid, ticks and labels; returns the data frame.
Frame draw_axes(ImDrawList* dl, ImVec2 origin, ImVec2 size, const AxisRange& xr,
                const AxisRange& yr, const char* x_label, const char* y_label,
                bool integer_x = false) {
    const float font = ImGui::GetFontSize();
    Frame f{{origin.x + font * 3.2f, origin.y + font * 0.4f},
            {origin.x + size.x - font * 0.4f, origin.y + size.y - font * 1.3f},
            xr,
            yr};
    dl->AddRectFilled(f.lo, f.hi, IM_COL32(255, 255, 255, 255));
    if (f.hi.x - f.lo.x < 10.0f || f.hi.y - f.lo.y < 10.0f) return f;
    const auto yt = nice_ticks(yr, std::max(2, static_cast<int>((f.hi.y - f.lo.y) / 28.0f)));
    const double ys = yt.size() > 1 ? yt[1] - yt[0] : 1.0;
    for (double t : yt) {
        const float y = f.py(t);
        dl->AddLine({f.lo.x, y}, {f.hi.x, y}, kGrid);
        const std::string label = format_tick(t, ys);
        const ImVec2 ts = ImGui::CalcTextSize(label.c_str());
        dl->AddText({f.lo.x - ts.x - 3.0f, y - ts.y * 0.5f}, kText, label.c_str());
    }
    auto xt = nice_ticks(xr, std::max(2, static_cast<int>((f.hi.x - f.lo.x) / 70.0f)));
    if (integer_x)  // counts (ages): no tick between two whole numbers
        std::erase_if(xt, [](double t) { return std::abs(t - std::round(t)) > 1e-9; });
    const double xs = xt.size() > 1 ? xt[1] - xt[0] : 1.0;
    for (double t : xt) {
        const float x = f.px(t);
        dl->AddLine({x, f.lo.y}, {x, f.hi.y}, kGrid);
        const std::string label = format_tick(t, xs);
        const ImVec2 ts = ImGui::CalcTextSize(label.c_str());
        dl->AddText({x - ts.x * 0.5f, f.hi.y + 1.0f}, kText, label.c_str());
    }
    dl->AddRect(f.lo, f.hi, kAxis);
    const ImVec2 xl = ImGui::CalcTextSize(x_label);
    dl->AddText({f.hi.x - xl.x - 2.0f, f.hi.y - xl.y - 1.0f}, IM_COL32(110, 110, 110, 255),
                x_label);
    dl->AddText({f.lo.x + 4.0f, f.lo.y + 1.0f}, kText, y_label);
    return f;
}

}  // namespace

std::optional<double> draw_time_plot(const char* id, const std::vector<double>& x,
                                     const std::vector<PlotCurve>& curves, double cursor_x,
                                     const char* title, const char* unit, ImVec2 size) {
    ImDrawList* dl = ImGui::GetWindowDrawList();
    const ImVec2 origin = ImGui::GetCursorScreenPos();
    area_button(id, size);
    const bool active = ImGui::IsItemActive();
    std::vector<double> ys;
    for (const auto& c : curves)
        if (c.y) ys.insert(ys.end(), c.y->begin(), c.y->end());
    AxisRange xr = x.size() > 1 ? AxisRange{x.front(), x.back()} : AxisRange{0.0, 1.0};
    const std::string label = std::string(title) + " (" + unit + ")";
    const Frame f = draw_axes(dl, origin, size, xr, fit_range(ys, 0.08), "t (s)", label.c_str());
    if (f.hi.x - f.lo.x < 10.0f || f.hi.y - f.lo.y < 10.0f) return std::nullopt;
    dl->PushClipRect(f.lo, f.hi, true);
    std::vector<ImVec2> points;
    for (const auto& c : curves) {
        if (!c.y || c.y->size() != x.size()) continue;
        if (c.dots) {
            for (std::size_t k = 0; k < x.size(); ++k)
                dl->AddCircleFilled({f.px(x[k]), f.py((*c.y)[k])}, 2.0f, c.color, 8);
            continue;
        }
        points.clear();
        // At most one point per pixel column: a long replay stays cheap to draw.
        const std::size_t stride =
            std::max<std::size_t>(1, x.size() / static_cast<std::size_t>(f.hi.x - f.lo.x + 1));
        for (std::size_t k = 0; k < x.size(); k += stride)
            points.push_back({f.px(x[k]), f.py((*c.y)[k])});
        if (points.size() > 1)
            dl->AddPolyline(points.data(), static_cast<int>(points.size()), c.color, 0, 1.5f);
    }
    const float cx = f.px(cursor_x);
    dl->AddLine({cx, f.lo.y}, {cx, f.hi.y}, kCursor, 2.0f);
    dl->PopClipRect();
    // Legend for several curves, at the top right.
    if (curves.size() > 1) {
        float at = f.hi.x - 4.0f;
        for (auto it = curves.rbegin(); it != curves.rend(); ++it) {
            const ImVec2 ts = ImGui::CalcTextSize(it->label);
            at -= ts.x;
            dl->AddText({at, f.lo.y + 1.0f}, it->color, it->label);
            at -= 8.0f;
        }
    }
    if (active) {
        const float mx = std::clamp(ImGui::GetIO().MousePos.x, f.lo.x, f.hi.x);
        return f.x_at(mx);
    }
    return std::nullopt;
}

std::optional<int> draw_scatter_plot(const char* id, const std::vector<ScatterPoint>& points,
                                     const char* x_label, const char* y_label, ImVec2 size,
                                     int* hovered, bool integer_x, std::vector<ImVec2>* screen) {
    ImDrawList* dl = ImGui::GetWindowDrawList();
    const ImVec2 origin = ImGui::GetCursorScreenPos();
    area_button(id, size);
    const bool item_hovered = ImGui::IsItemHovered();
    const bool clicked = ImGui::IsItemClicked();
    std::vector<double> xs, ys;
    for (const auto& p : points) {
        xs.push_back(p.x);
        ys.push_back(p.y);
    }
    AxisRange xr = fit_range(xs, 0.08);
    if (xr.span() < 1.0) xr = {xr.min - 0.5, xr.max + 0.5};
    const Frame f =
        draw_axes(dl, origin, size, xr, fit_range(ys, 0.08), x_label, y_label, integer_x);
    if (hovered) *hovered = -1;
    if (screen) screen->clear();
    if (f.hi.x - f.lo.x < 10.0f || f.hi.y - f.lo.y < 10.0f) return std::nullopt;
    const ImVec2 mouse = ImGui::GetIO().MousePos;
    int nearest = -1;
    float best = 64.0f;  // 8 px squared
    dl->PushClipRect(f.lo, f.hi, true);
    for (std::size_t k = 0; k < points.size(); ++k) {
        const auto& p = points[k];
        const ImVec2 at{f.px(p.x), f.py(p.y)};
        if (screen) screen->push_back(at);
        dl->AddCircleFilled(at, p.radius, p.color);
        if (p.ring) dl->AddCircle(at, p.radius + 3.0f, IM_COL32(20, 20, 20, 255), 0, 1.5f);
        const float d2 = (at.x - mouse.x) * (at.x - mouse.x) + (at.y - mouse.y) * (at.y - mouse.y);
        if (item_hovered && d2 < best) {
            best = d2;
            nearest = static_cast<int>(k);
        }
    }
    dl->PopClipRect();
    if (hovered) *hovered = nearest;
    if (clicked && nearest >= 0) return nearest;
    return std::nullopt;
}

}  // namespace bhm::app::gui
