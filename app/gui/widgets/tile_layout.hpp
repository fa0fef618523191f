#pragma once
// The tiled layout's arithmetic (ImGui 1.86 has no docking): the sizes the user chose (settings)
// are preferences, never overwritten by a small window; each frame fits them into the display,
// so a tiny resize squeezes the tiles only while the window is small. Splitters on the inner
// edges change the preferences, bounded.
#include "app/gui/studio_settings.hpp"

namespace bhm::app::gui {

//! The tiles' sizes this frame, in pixels.
struct TileLayout {
    float left = 0.0f, right = 0.0f;  //!< column widths
    float view = 0.0f;                //!< 3D view height (centre column)
    float bottom = 0.0f;              //!< replay panel height
    float run = 0.0f, plot = 0.0f;    //!< right column: Run and Fitness heights
    float population = 0.0f;          //!< right column: what is left under them
    bool operator==(const TileLayout&) const = default;
};

//! Smallest sizes a tile keeps while there is room.
inline constexpr float kMinSide = 120.0f, kMinCentre = 200.0f, kMinBottom = 60.0f,
                       kMinView = 120.0f, kMinRun = 80.0f, kMinPlot = 80.0f, kMinPopulation = 60.0f;

//! Fits the preferences into a width x height area (the space between menu and status bars):
//! when they do not fit, the side columns (and the right column's tiles) shrink in proportion.
TileLayout fit_layout(const PanelLayout& preferred, float width, float height);

//! Splitters: the preference after dragging an edge by delta pixels from the fitted layout, kept
//! within what the area allows (a drag can never push a tile off screen or run away).
enum class Splitter { Left, Right, Replay, RunPlot, PlotPopulation };
void drag_splitter(PanelLayout& preferred, const TileLayout& fitted, Splitter which, float delta,
                   float width, float height);

}  // namespace bhm::app::gui
