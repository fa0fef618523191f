#pragma once
// The shown body's geometry for other tools, as `bhm export` writes it (evo/formats): its surface
// as a closed mesh (STL, or OBJ + MTL with a group per material), at rest or deformed at the
// replay's current time, and its replay as a ParaView series. Failures go to the status line.
#include <string>

#include "app/gui/studio.hpp"

namespace bhm::app::gui {

//! The surface mesh of the body shown: `deformed` at the replay time (a simulated body), else at
//! rest (the champion will do when nothing is simulated yet). .stl or .obj by the path's ending.
bool export_mesh(Studio& studio, const std::string& path, bool deformed);
//! The shown body's replay as DIR/series.pvd, DIR/frame-NNNNN.vtu and DIR/com_path.vtp.
bool export_vtk_series(Studio& studio, const std::string& dir);

}  // namespace bhm::app::gui
