#pragma once
// The fitness plot (ImGui 1.86 has no plotting library: drawn with ImDrawList): best and median
// fitness per generation, axes fitted to the data with round ticks, vertical markers where the
// rules changed, and the values of the generation under the mouse.
#include <optional>
#include <vector>

#include <imgui.h>

#include "app/gui/evolution_snapshot.hpp"
#include "app/gui/plot_axes.hpp"

namespace bhm::app::gui {

struct FitnessPlot {
    std::optional<int> hovered_generation;  //!< set by draw() while the mouse is over the plot

    //! Draws into a size x height area at the cursor; y_unit labels the axis ("deg", "voxels").
    void draw(const std::vector<GenerationRecord>& history, const std::vector<RuleChange>& changes,
              ImVec2 size, const char* y_unit);
};

//! Index of the record nearest to generation g (history sorted by generation); -1 when empty.
int nearest_record(const std::vector<GenerationRecord>& history, double generation);

}  // namespace bhm::app::gui
