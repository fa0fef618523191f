#pragma once
// What a click in the 3D view does (the viewport panel and scripts): an edit of the experiment in
// Workspace mode, the inspected voxel in Simulation mode. The picking itself is view/'s.
#include <glm/vec2.hpp>

#include "app/gui/studio.hpp"

namespace bhm::app::gui {

//! What a left click at `pixel` (view coordinates, top-left origin) does: cycle a face or paint a
//! cell in Workspace mode; in Simulation mode pick the voxel of the shown body under it, as posed
//! at the replay time (studio.bodies.inspected_voxel; a click beside the body clears it). Returns
//! true when it changed the experiment.
bool click_in_view(Studio& studio, glm::vec2 pixel, bool shift);

}  // namespace bhm::app::gui
