#include "app/gui/widgets/tile_layout.hpp"

#include <algorithm>

namespace bhm::app::gui {

namespace {

// Shrinks a and b in proportion so a + b <= room, each at least lo (if room allows).
void fit_pair(float& a, float& b, float room, float lo) {
    if (a + b <= room) return;
    const float scale = std::max(0.0f, room) / std::max(1.0f, a + b);
    a = std::max(std::min(lo, room * 0.5f), a * scale);
    b = std::max(std::min(lo, room * 0.5f), b * scale);
}

// The centre column's least width and the replay panel's greatest height in this area.
float min_centre(float width) {
    return std::max(kMinCentre,
                    (width < kCollapseLeftBelow ? kCentreShareNarrow : kCentreShare) * width);
}
float max_bottom(float height) {
    return std::max(kMinBottom, std::min(height - kMinView, (1.0f - kViewShare) * height));
}

}  // namespace

TileLayout fit_layout(const PanelLayout& p, float width, float height) {
    TileLayout t;
    t.right = std::max(kMinSide, p.right_px);
    if (width < kCollapseLeftBelow) {
        t.left_collapsed = true;
        t.left = kCollapsedSide;
        // The left column folded, the view takes half the width: the right column (the run's
        // state) keeps what is left, up to its preference.
        const float centre = std::max(kMinCentre, kCentreShareNarrow * width);
        t.right = std::max(std::min(kMinSide, width * 0.5f),
                           std::min(t.right, width - kCollapsedSide - centre));
    } else {
        t.left = std::max(kMinSide, p.left_px);
        fit_pair(t.left, t.right, width - min_centre(width), kMinSide);
    }
    t.bottom = std::clamp(p.bottom_px, kMinBottom, max_bottom(height));
    t.view = std::max(16.0f, height - t.bottom);
    t.run = std::max(kMinRun, p.run_px);
    t.plot = std::max(kMinPlot, p.plot_px);
    fit_pair(t.run, t.plot, height - kMinPopulation, kMinRun);
    t.population = std::max(16.0f, height - t.run - t.plot);
    return t;
}

void drag_splitter(PanelLayout& p, const TileLayout& t, Splitter which, float delta, float width,
                   float height) {
    switch (which) {
        case Splitter::Left:
            if (t.left_collapsed) break;  // a strip: nothing to drag
            p.left_px = std::clamp(t.left + delta, kMinSide,
                                   std::max(kMinSide, width - t.right - min_centre(width)));
            p.right_px = t.right;
            break;
        case Splitter::Right:  // the edge moves left: the right column widens
            p.right_px =
                std::clamp(t.right - delta, kMinSide,
                           std::max(kMinSide, width - std::max(t.left, kCollapsedSide) -
                                                  min_centre(width)));
            if (!t.left_collapsed) p.left_px = t.left;
            break;
        case Splitter::Replay:  // the edge moves up: the replay panel grows
            p.bottom_px = std::clamp(t.bottom - delta, kMinBottom, max_bottom(height));
            break;
        case Splitter::RunPlot:
            p.run_px = std::clamp(t.run + delta, kMinRun,
                                  std::max(kMinRun, height - t.plot - kMinPopulation));
            p.plot_px = t.plot;
            break;
        case Splitter::PlotPopulation:
            p.plot_px = std::clamp(t.plot + delta, kMinPlot,
                                   std::max(kMinPlot, height - t.run - kMinPopulation));
            p.run_px = t.run;
            break;
    }
}

}  // namespace bhm::app::gui
