#pragma once
// The tiled layout's arithmetic (ImGui 1.86 has no docking): the sizes the user chose (settings)
// are preferences, never overwritten by a small window; each frame fits them into the display,
// so a tiny resize squeezes the tiles only while the window is small. Splitters on the inner
// edges change the preferences, bounded.
#include "app/gui/settings/studio_settings.hpp"

namespace bhm::app::gui {

//! The tiles' sizes this frame, in pixels.
struct TileLayout {
    float left = 0.0f, right = 0.0f;  //!< column widths
    float view = 0.0f;                //!< 3D view height (centre column)
    float bottom = 0.0f;              //!< replay panel height
    float run = 0.0f, plot = 0.0f;    //!< right column: Run and Fitness heights
    float population = 0.0f;          //!< right column: what is left under them
    //! A narrow window: the left column is a strip with a button that opens it over the view.
    bool left_collapsed = false;
    bool operator==(const TileLayout&) const = default;
};

//! Smallest sizes a tile keeps while there is room.
inline constexpr float kMinSide = 120.0f, kMinCentre = 200.0f, kMinBottom = 60.0f,
                       kMinView = 120.0f, kMinRun = 80.0f, kMinPlot = 80.0f;
//! The Analysis tile (under Run and Fitness) keeps its tab row and about eight lines under it:
//! with 60 px, at 900 x 600 it was only its tab row, so population, calibration and FEM could
//! not be reached (issue 39, M5). Run and Fitness give way first.
inline constexpr float kMinPopulation = 200.0f;
//! The 3D view keeps priority in a small window (issue 25 item 7: at 800 x 500 it was 170 x 120
//! px): the centre column keeps at least this share of the width and the view this share of the
//! centre's height; below kCollapseLeftBelow px of width the left column folds into a strip of
//! kCollapsedSide px (its panels open over the view from there) and the centre keeps half.
inline constexpr float kCentreShare = 0.3f, kCentreShareNarrow = 0.5f, kViewShare = 0.7f,
                       kCollapseLeftBelow = 1000.0f, kCollapsedSide = 28.0f;

//! Fits the preferences into a width x height area (the space between menu and status bars):
//! when they do not fit, the side columns (and the right column's tiles) shrink in proportion,
//! never below the centre's share; a narrow window folds the left column.
TileLayout fit_layout(const PanelLayout& preferred, float width, float height);

//! Splitters: the preference after dragging an edge by delta pixels from the fitted layout, kept
//! within what the area allows (a drag can never push a tile off screen or run away).
enum class Splitter { Left, Right, Replay, RunPlot, PlotPopulation };
void drag_splitter(PanelLayout& preferred, const TileLayout& fitted, Splitter which, float delta,
                   float width, float height);

}  // namespace bhm::app::gui
