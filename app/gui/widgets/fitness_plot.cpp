#include "app/gui/widgets/fitness_plot.hpp"
#include "app/gui/widgets/ui_widgets.hpp"

#include <algorithm>
#include <array>
#include <cmath>
#include <string>

namespace bhm::app::gui {

namespace {

constexpr ImU32 kBestColor = IM_COL32(214, 69, 56, 255);
constexpr ImU32 kMedianColor = IM_COL32(60, 110, 190, 255);
constexpr ImU32 kMarkerColor = IM_COL32(46, 160, 80, 220);
constexpr ImU32 kGridColor = IM_COL32(0, 0, 0, 28);
constexpr ImU32 kAxisColor = IM_COL32(60, 60, 60, 255);
constexpr ImU32 kTextColor = IM_COL32(40, 40, 40, 255);
constexpr std::array<ImU32, 5> kOverlayColors = {
    IM_COL32(120, 120, 120, 200), IM_COL32(150, 110, 60, 200), IM_COL32(90, 140, 120, 200),
    IM_COL32(140, 100, 160, 200), IM_COL32(100, 130, 170, 200)};

}  // namespace

int nearest_record(const std::vector<GenerationRecord>& history, double generation) {
    if (history.empty()) return -1;
    const auto it =
        std::lower_bound(history.begin(), history.end(), generation,
                         [](const GenerationRecord& r, double g) { return r.generation < g; });
    if (it == history.end()) return static_cast<int>(history.size()) - 1;
    if (it == history.begin()) return 0;
    const auto before = it - 1;
    return static_cast<int>(
        (generation - before->generation <= it->generation - generation ? before : it) -
        history.begin());
}

std::vector<MeasureSeries> split_by_measure(const EvolutionSnapshot& run) {
    std::vector<MeasureSeries> out;
    for (const auto& r : run.history) {
        const auto measure = measure_at(run, r.generation);
        auto it = std::find_if(out.begin(), out.end(),
                               [&](const MeasureSeries& m) { return m.measure == measure; });
        if (it == out.end()) {
            out.push_back({measure, {}});
            it = out.end() - 1;
        }
        it->records.push_back(r);
    }
    return out;
}

void FitnessPlot::draw(const std::vector<GenerationRecord>& history,
                       const std::vector<RuleChangeNote>& changes, ImVec2 size, const char* y_unit,
                       const std::vector<OverlayCurve>& overlays) {
    hovered_generation.reset();
    ImDrawList* dl = ImGui::GetWindowDrawList();
    const ImVec2 origin = ImGui::GetCursorScreenPos();
    area_button("fitness plot", size);
    const bool hovered = ImGui::IsItemHovered();
    const float font = ImGui::GetFontSize();
    const ImVec2 lo{origin.x + font * 3.6f, origin.y + font * 0.6f};
    const ImVec2 hi{origin.x + size.x - font * 0.6f, origin.y + size.y - font * 2.6f};
    dl->AddRectFilled(lo, hi, IM_COL32(255, 255, 255, 255));
    if (hi.x - lo.x < 20.0f || hi.y - lo.y < 20.0f) return;

    std::vector<double> ys, xs;
    for (const auto& r : history) {
        ys.push_back(r.best_fitness);
        ys.push_back(r.median_fitness);
        xs.push_back(r.generation);
    }
    for (const auto& o : overlays)
        for (const auto& r : o.records) {
            ys.push_back(r.best_fitness);
            xs.push_back(r.generation);
        }
    const AxisRange yr = fit_range(ys, 0.06);
    AxisRange xr = xs.empty() ? AxisRange{0.0, 10.0} : fit_range(xs, 0.0);
    if (xs.size() < 2) xr = {0.0, std::max(1.0, xr.max + 1.0)};
    auto px = [&](double g) { return lo.x + float((g - xr.min) / xr.span()) * (hi.x - lo.x); };
    auto py = [&](double v) { return hi.y - float((v - yr.min) / yr.span()) * (hi.y - lo.y); };

    // Grid and tick labels.
    // Thinned to what the axis has room for: a squeezed plot shows fewer labels, never overlapping.
    const auto yticks = spaced_ticks(yr, hi.y - lo.y, font * 1.4f, 5);
    const double ystep = yticks.size() > 1 ? yticks[1] - yticks[0] : 1.0;
    for (double t : yticks) {
        const float y = py(t);
        dl->AddLine({lo.x, y}, {hi.x, y}, kGridColor);
        const std::string label = format_tick(t, ystep);
        const ImVec2 ts = ImGui::CalcTextSize(label.c_str());
        dl->AddText({lo.x - ts.x - 4.0f, y - ts.y * 0.5f}, kTextColor, label.c_str());
    }
    const float x_label = ImGui::CalcTextSize(format_tick(xr.max, 1.0).c_str()).x + font;
    auto xticks = spaced_ticks(xr, hi.x - lo.x, x_label, 6);
    std::erase_if(xticks, [](double t) { return std::abs(t - std::round(t)) > 1e-9; });
    for (double t : xticks) {
        const float x = px(t);
        dl->AddLine({x, lo.y}, {x, hi.y}, kGridColor);
        const std::string label = format_tick(t, 1.0);
        const ImVec2 ts = ImGui::CalcTextSize(label.c_str());
        dl->AddText({x - ts.x * 0.5f, hi.y + 2.0f}, kTextColor, label.c_str());
    }
    dl->AddRect(lo, hi, kAxisColor);
    const char* xlabel = "generation";
    const ImVec2 xs_size = ImGui::CalcTextSize(xlabel);
    dl->AddText({0.5f * (lo.x + hi.x) - 0.5f * xs_size.x, hi.y + font * 1.2f}, kTextColor, xlabel);
    dl->AddText({origin.x, origin.y + size.y - font * 1.2f}, kTextColor, y_unit);

    // Constraint-change markers: a vertical dashed green line at the generation.
    for (const auto& c : changes) {
        const float x = px(c.generation);
        if (x < lo.x - 1.0f || x > hi.x + 1.0f) continue;
        for (float y = lo.y; y < hi.y; y += 8.0f)
            dl->AddLine({x, y}, {x, std::min(hi.y, y + 4.0f)}, kMarkerColor, 2.0f);
        dl->AddTriangleFilled({x - 5.0f, lo.y}, {x + 5.0f, lo.y}, {x, lo.y + 7.0f}, kMarkerColor);
    }

    // Curves: other runs thin and pale, then the median, the current best bold on top.
    dl->PushClipRect(lo, hi, true);
    for (std::size_t k = 0; k < overlays.size(); ++k) {
        std::vector<ImVec2> points;
        for (const auto& r : overlays[k].records)
            points.push_back({px(r.generation), py(r.best_fitness)});
        const ImU32 color = kOverlayColors[k % kOverlayColors.size()];
        if (points.size() == 1)
            dl->AddCircleFilled(points[0], 2.0f, color);
        else if (!points.empty())
            dl->AddPolyline(points.data(), static_cast<int>(points.size()), color, 0, 1.0f);
    }
    for (int pass = 0; pass < 2; ++pass) {
        std::vector<ImVec2> points;
        for (const auto& r : history)
            points.push_back({px(r.generation), py(pass == 0 ? r.median_fitness : r.best_fitness)});
        const ImU32 color = pass == 0 ? kMedianColor : kBestColor;
        if (points.size() == 1)
            dl->AddCircleFilled(points[0], 3.0f, color);
        else if (!points.empty())
            dl->AddPolyline(points.data(), static_cast<int>(points.size()), color, 0,
                            pass == 0 ? 2.0f : 3.0f);
    }
    dl->PopClipRect();

    // Legend.
    const ImVec2 legend{lo.x + 8.0f, lo.y + 6.0f};
    dl->AddLine({legend.x, legend.y + font * 0.5f}, {legend.x + 18.0f, legend.y + font * 0.5f},
                kBestColor, 2.5f);
    dl->AddText({legend.x + 22.0f, legend.y}, kTextColor, "best");
    const float second = legend.x + 22.0f + ImGui::CalcTextSize("best").x + 14.0f;
    dl->AddLine({second, legend.y + font * 0.5f}, {second + 18.0f, legend.y + font * 0.5f},
                kMedianColor, 2.5f);
    dl->AddText({second + 22.0f, legend.y}, kTextColor, "median");
    if (!changes.empty()) {
        const float third = second + 22.0f + ImGui::CalcTextSize("median").x + 14.0f;
        dl->AddLine({third + 9.0f, legend.y}, {third + 9.0f, legend.y + font}, kMarkerColor, 2.0f);
        dl->AddText({third + 22.0f, legend.y}, kTextColor, "rules changed");
    }

    if (!overlays.empty()) {
        const std::string text = "thin: " + std::to_string(overlays.size()) +
                                 (overlays.size() == 1 ? " other run" : " other runs");
        const ImVec2 ts = ImGui::CalcTextSize(text.c_str());
        dl->AddText({hi.x - ts.x - 6.0f, hi.y - ts.y - 4.0f}, kTextColor, text.c_str());
    }

    // Hover: the nearest generation's values.
    if (hovered && !history.empty()) {
        const ImVec2 mouse = ImGui::GetIO().MousePos;
        const double g = xr.min + (mouse.x - lo.x) / (hi.x - lo.x) * xr.span();
        const int i = nearest_record(history, g);
        const auto& r = history[static_cast<std::size_t>(i)];
        hovered_generation = r.generation;
        const float x = px(r.generation);
        dl->AddLine({x, lo.y}, {x, hi.y}, IM_COL32(0, 0, 0, 90));
        dl->AddCircleFilled({x, py(r.best_fitness)}, 4.0f, kBestColor);
        dl->AddCircleFilled({x, py(r.median_fitness)}, 4.0f, kMedianColor);
        std::string changed;
        for (const auto& c : changes)
            if (c.generation == r.generation) changed += "\n" + c.description;
        ImGui::SetTooltip("generation %d\nbest   %.4g %s\nmedian %.4g %s\n%lld simulations%s",
                          r.generation, r.best_fitness, y_unit, r.median_fitness, y_unit,
                          static_cast<long long>(r.evaluations), changed.c_str());
    }
}

}  // namespace bhm::app::gui
