#pragma once
// The fitness plot (ImGui 1.86 has no plotting library: drawn with ImDrawList): best and median
// fitness per generation, axes fitted to the data with round ticks, vertical markers where the
// rules changed, and the values of the generation under the mouse.
#include <optional>
#include <string>
#include <vector>

#include <imgui.h>

#include "app/gui/session/evolution_snapshot.hpp"
#include "app/gui/widgets/plot_axes.hpp"

namespace bhm::app::gui {

//! Another run's best-fitness curve drawn thin behind the current run's (paper Figure 14).
struct OverlayCurve {
    std::string label;
    std::vector<GenerationRecord> records;
};

//! A fitness plot is never drawn lower than this many font heights: several measures go to tabs
//! instead (issue 25 item 7: after a rule change each plot had about 30 px).
inline constexpr float kMinPlotFonts = 8.0f;

struct FitnessPlot {
    std::optional<int> hovered_generation;  //!< set by draw() while the mouse is over the plot
    std::size_t measures_seen = 0;  //!< plots drawn last frame: a new measure's tab is selected

    //! Draws into a size x height area at the cursor; y_unit labels the axis ("deg", "voxels").
    //! Overlays (other runs, same measure) are drawn thin; the axes fit all curves.
    void draw(const std::vector<GenerationRecord>& history, const std::vector<RuleChangeNote>& changes,
              ImVec2 size, const char* y_unit, const std::vector<OverlayCurve>& overlays = {});
};

//! The generations of one measure (a run whose rules changed has several).
struct MeasureSeries {
    evo::FitnessMeasure measure = evo::FitnessMeasure::ComFinal3d;
    std::vector<GenerationRecord> records;
};
//! Splits a run's history by the measure each generation was scored under (measure_at), in the
//! order the measures first appear: values of different measures never share a curve or an axis.
std::vector<MeasureSeries> split_by_measure(const EvolutionSnapshot& run);

//! Index of the record nearest to generation g (history sorted by generation); -1 when empty.
int nearest_record(const std::vector<GenerationRecord>& history, double generation);

}  // namespace bhm::app::gui
