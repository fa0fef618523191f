#include "app/gui/view/viewport.hpp"

#include <glm/glm.hpp>

#include "app/gui/view/scene.hpp"
#include "app/gui/view/track_points.hpp"
#include "engine/replay.hpp"

namespace bhm::app::gui {

namespace {

constexpr glm::vec4 kHoverFace{1.0f, 0.78f, 0.10f, 0.30f};
constexpr glm::vec4 kHoverCell{1.0f, 0.62f, 0.0f, 1.0f};
constexpr glm::vec4 kPickedVoxel{0.93f, 0.49f, 0.13f, 1.0f};  // the inspector box's orange
constexpr glm::vec4 kFixedFaceTint{0.10f, 0.62f, 0.22f, 0.28f};

LatticeBox workspace_box(const evo::Experiment& e) {
    return {e.workspace_size, e.voxel_size_m};
}

constexpr glm::vec4 kMeasured{0.05f, 0.05f, 0.05f, 1.0f};
constexpr glm::vec4 kSimulatedPoint{0.93f, 0.49f, 0.13f, 1.0f};

// The measured track over the replay (Calibrate tab): each tracked point's measured path up to
// the replay time (black, drawn over the body) with a black dot where it is now, and an orange
// dot on the simulated point, so the gap between the two is what the misfit measures. Only over
// the body the track was loaded onto.
void add_track_overlay(render::DrawList& list, const Studio& s) {
    const auto& c = s.calibration;
    const auto snap = c.snapshot;
    if (!c.track || !s.bodies.shown || s.bodies.shown->framed_body != c.framed_body || !snap ||
        !snap->preview || snap->track != c.track)
        return;
    const auto& track = *c.track;
    const auto& preview = *snap->preview;
    const double t = s.clock.time_s;
    for (std::size_t i = 0; i < track.points.size(); ++i) {
        std::optional<glm::vec3> last;
        for (double tk : track.t_s) {
            if (tk > t) break;
            const auto p = measured_point_at(track, preview, i, tk);
            if (!p) break;
            const glm::vec3 here((*p)[0], (*p)[1], (*p)[2]);
            if (last) {
                list.lines_on_top.push_back({*last, kMeasured, 2.0f});
                list.lines_on_top.push_back({here, kMeasured, 2.0f});
            }
            last = here;
        }
        if (const auto now = measured_point_at(track, preview, i, t)) {
            render::Marker m;
            m.position = glm::vec3((*now)[0], (*now)[1], (*now)[2]);
            m.color = kMeasured;
            m.shape = render::MarkerShape::Dot;
            m.size_px = 7.0f;
            list.markers.push_back(m);
            if (const auto sim = simulated_point_at(track, preview, i, t)) {
                m.position = glm::vec3((*sim)[0], (*sim)[1], (*sim)[2]);
                m.color = kSimulatedPoint;
                m.size_px = 5.0f;
                list.markers.push_back(m);
            }
        }
    }
}

// Appends `from` moved by `offset` (a second body beside the first).
void append_offset(render::DrawList& into, const render::DrawList& from, glm::vec3 offset) {
    for (auto box : from.boxes) {
        box.centre += offset;
        into.boxes.push_back(box);
    }
    for (auto box : from.translucent_boxes) {
        box.centre += offset;
        into.translucent_boxes.push_back(box);
    }
    auto move = [&](const auto& src, auto& dst) {
        for (auto v : src) {
            v.position += offset;
            dst.push_back(v);
        }
    };
    move(from.lines, into.lines);
    move(from.lines_on_top, into.lines_on_top);
    move(from.floor, into.floor);
    move(from.floor_lines, into.floor_lines);
    move(from.translucent_triangles, into.translucent_triangles);
    move(from.markers, into.markers);
    if (from.bounds.valid) {
        into.bounds.add(from.bounds.min + offset);
        into.bounds.add(from.bounds.max + offset);
    }
}

}  // namespace

const evo::Body* painter_context_body(const Studio& s) {
    if (!s.painter.show_champion || !s.run.snapshot || !s.run.snapshot->has_champion ||
        !s.run.snapshot->champion.body)
        return nullptr;
    return s.run.snapshot->champion.body.get();
}

render::DrawList workspace_draw_list(const evo::Experiment& e, const PainterState& painter,
                                     const evo::Body* context_body, bool show_edges) {
    render::Scene scene = workspace_scene(e, painter, context_body);
    scene.options.show_edges = show_edges;
    render::DrawList list = render::build_draw_list(scene);
    lift_face_tints(list, e.workspace_size, e.voxel_size_m);
    // The renderer's fixed-face tint is faint over a light background; the painter's job is to
    // show which faces hold the body, so fixed faces get a second green layer here.
    for (int f = 0; f < 6; ++f)
        if (e.boundary.faces[static_cast<std::size_t>(f)] == evo::BoundaryKind::Fixed)
            add_face_highlight(list, e.workspace_size, e.voxel_size_m, static_cast<evo::Face>(f),
                               kFixedFaceTint);
    return list;
}

const FemVerification* fem_overlay(const Studio& studio) {
    const auto& v = studio.verify.result;
    if (!studio.verify.ghost || !v || !studio.bodies.shown || v->id != studio.bodies.shown->id ||
        studio.view.mode != ViewMode::Simulation || v->fem_shape.empty())
        return nullptr;
    if (studio.verify.load < 0 || studio.verify.load >= static_cast<int>(v->fem_shape.size()))
        return nullptr;
    return v.get();
}

render::DrawList build_view_draw_list(const Studio& s) {
    const auto& e = s.document.experiment();
    if (s.view.mode == ViewMode::Simulation && s.bodies.shown) {
        const auto& se = s.bodies.shown->experiment;
        render::Scene scene = simulation_scene(*s.bodies.shown, s.clock.time_s, s.view);
        // Verify in FEM: our static shape under the chosen load, the FEM's as a ghost over it.
        if (const FemVerification* v = fem_overlay(s)) apply_fem_overlay(scene, *v, s.verify.load);
        render::DrawList list = render::build_draw_list(scene);
        for (int f = 0; f < 6; ++f)
            if (se.boundary.faces[static_cast<std::size_t>(f)] == evo::BoundaryKind::Fixed)
                add_fixed_face_hatch(list, se.workspace_size, se.voxel_size_m,
                                     static_cast<evo::Face>(f));
        if (s.bodies.compared && !s.view.split) {
            // Side by side: the compared body on the same clock, one workspace further along +y.
            const render::DrawList other = compared_view_draw_list(s);
            const float gap = static_cast<float>((se.workspace_size[1] + 2) * se.voxel_size_m);
            append_offset(list, other, {0.0f, gap, 0.0f});
        }
        // The voxel clicked (read at the bottom of the view), as posed now.
        if (inspected_voxel(s) && !fem_overlay(s))
            add_posed_voxel_highlight(list, engine::pose_at(s.bodies.shown->replay, s.clock.time_s),
                                      s.bodies.inspected_voxel, kPickedVoxel);
        add_track_overlay(list, s);
        return list;
    }
    render::DrawList list =
        workspace_draw_list(e, s.painter, painter_context_body(s), s.view.show_edges);
    if (s.painter.tool == PainterTool::Faces && s.painter.hovered_face)
        add_face_highlight(list, e.workspace_size, e.voxel_size_m, *s.painter.hovered_face,
                           kHoverFace);
    if (s.painter.tool == PainterTool::Voxels && s.painter.hovered_cell)
        add_cell_highlight(list, *s.painter.hovered_cell, e.voxel_size_m, kHoverCell);
    return list;
}

bool split_view_active(const Studio& s) {
    return s.view.mode == ViewMode::Simulation && s.view.split && s.bodies.compared &&
           s.bodies.shown;
}

render::DrawList compared_view_draw_list(const Studio& s) {
    if (!s.bodies.compared) return {};
    const auto& ce = s.bodies.compared->experiment;
    render::DrawList list =
        render::build_draw_list(simulation_scene(*s.bodies.compared, s.clock.time_s, s.view));
    for (int f = 0; f < 6; ++f)
        if (ce.boundary.faces[static_cast<std::size_t>(f)] == evo::BoundaryKind::Fixed)
            add_fixed_face_hatch(list, ce.workspace_size, ce.voxel_size_m,
                                 static_cast<evo::Face>(f));
    return list;
}

void frame_view_camera(Studio& s, const render::DrawList& list, float aspect) {
    if (!s.view.camera_needs_framing) return;
    render::Bounds bounds = list.workspace_bounds.valid ? list.workspace_bounds : list.bounds;
    if (s.view.mode == ViewMode::Simulation &&
        (s.view.show_start_beside || (s.bodies.compared && !s.view.split)))
        bounds.add(list.bounds);
    render::frame_bounds(s.view.camera, bounds, aspect);
    s.view.camera.distance_m /= std::max(0.05f, s.view.zoom);
    s.view.camera_needs_framing = false;
}

void update_hover(Studio& s, std::optional<glm::vec2> pixel) {
    auto& p = s.painter;
    p.hovered_face.reset();
    p.hovered_cell.reset();
    if (!pixel || s.view.mode != ViewMode::Workspace || s.view.size_px.x < 1.0f) return;
    const auto& e = s.document.experiment();
    const Ray ray = ray_through_pixel(s.view.camera, *pixel, s.view.size_px);
    if (p.tool == PainterTool::Faces) {
        if (auto hit = pick_box_face(ray, workspace_box(e))) p.hovered_face = hit->face;
        return;
    }
    const auto occupied = painter_occupancy(e, painter_context_body(s));
    const auto box = workspace_box(e);
    auto hit = pick_cell(ray, box, p.slice, [&](const std::array<int, 3>& c) {
        return occupied[static_cast<std::size_t>(
                   c[0] + e.workspace_size[0] * (c[1] + e.workspace_size[1] * c[2]))] != 0;
    });
    if (hit) p.hovered_cell = hit->cell;
}

std::optional<VoxelReading> inspected_voxel(const Studio& s) {
    if (s.bodies.inspected_voxel < 0 || !s.bodies.inspected_body ||
        s.bodies.inspected_body != s.bodies.shown)
        return {};
    const SimulatedBody& b = *s.bodies.shown;
    const engine::Replay& r = b.replay;
    const auto v = static_cast<std::size_t>(s.bodies.inspected_voxel);
    if (v >= r.voxel_cell.size() || r.frames.empty()) return {};
    VoxelReading out;
    out.voxel = s.bodies.inspected_voxel;
    const int cell = r.voxel_cell[v];
    out.cell = {cell % r.nx, (cell / r.nx) % r.ny, cell / (r.nx * r.ny)};
    out.material = r.voxel_material[v];
    if (out.material >= 1 && out.material <= static_cast<int>(b.experiment.materials.size()))
        out.material_name = b.experiment.materials[static_cast<std::size_t>(out.material - 1)].name;
    out.held = v < r.voxel_fixed.size() && r.voxel_fixed[v] != 0;
    // The values the colour modes show at this time (one source for both).
    const int frame = frame_index_at(r, s.clock.time_s);
    auto value = [&](ColorBy by) {
        return voxel_scalars(by, b.experiment, r, frame, b.series, b.drive).values[v];
    };
    out.displacement_vox = value(ColorBy::Displacement);
    out.strain = value(ColorBy::Strain);
    out.actuation = value(ColorBy::Actuation);
    out.fibre_axis = v < b.drive.fibre_axis.size() ? b.drive.fibre_axis[v] : -1;
    return out;
}

}  // namespace bhm::app::gui
