#include "render/renderer.hpp"

#include <glad/gl.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <cstddef>
#include <vector>

#include <glm/glm.hpp>
#include <glm/gtc/matrix_transform.hpp>

#include "render/gl_check.hpp"
#include "render/overlay.hpp"
#include "render/shader_program.hpp"

namespace bhm::render {

namespace {

struct CubeVertex {
    glm::vec3 corner;
    glm::vec3 normal;
};

// 36 vertices of a unit cube centred at the origin, counter-clockwise seen from outside.
std::vector<CubeVertex> unit_cube() {
    std::vector<CubeVertex> vertices;
    for (int axis = 0; axis < 3; ++axis) {
        for (int sign = -1; sign <= 1; sign += 2) {
            glm::vec3 n(0.0f);
            n[axis] = static_cast<float>(sign);
            // Two tangents with t1 x t2 = n, so the winding faces outward.
            glm::vec3 t1(0.0f), t2(0.0f);
            t1[(axis + 1) % 3] = 1.0f;
            t2[(axis + 2) % 3] = static_cast<float>(sign);
            const glm::vec3 c = 0.5f * n;
            const glm::vec3 q[4] = {c - 0.5f * t1 - 0.5f * t2, c + 0.5f * t1 - 0.5f * t2,
                                    c + 0.5f * t1 + 0.5f * t2, c - 0.5f * t1 + 0.5f * t2};
            for (int i : {0, 1, 2, 0, 2, 3})
                vertices.push_back({q[i], n});
        }
    }
    return vertices;
}

// A five-pointed star, point up, as a triangle fan around its centre (outer radius 1).
std::vector<glm::vec2> star_triangles() {
    constexpr float kPi = 3.14159265358979f;
    std::array<glm::vec2, 10> rim;
    for (int i = 0; i < 10; ++i) {
        const float radius = (i % 2 == 0) ? 1.0f : 0.42f;
        const float angle = 0.5f * kPi + static_cast<float>(i) * kPi / 5.0f;
        rim[static_cast<std::size_t>(i)] = radius * glm::vec2(std::cos(angle), std::sin(angle));
    }
    std::vector<glm::vec2> triangles;
    for (int i = 0; i < 10; ++i) {
        triangles.push_back({0.0f, 0.0f});
        triangles.push_back(rim[static_cast<std::size_t>(i)]);
        triangles.push_back(rim[static_cast<std::size_t>((i + 1) % 10)]);
    }
    return triangles;
}

// A disc of outer radius 1 as a triangle fan around its centre.
std::vector<glm::vec2> dot_triangles() {
    constexpr float kPi = 3.14159265358979f;
    constexpr int kSides = 20;
    std::vector<glm::vec2> triangles;
    for (int i = 0; i < kSides; ++i) {
        const float a0 = 2.0f * kPi * static_cast<float>(i) / kSides;
        const float a1 = 2.0f * kPi * static_cast<float>(i + 1) / kSides;
        triangles.push_back({0.0f, 0.0f});
        triangles.push_back({std::cos(a0), std::sin(a0)});
        triangles.push_back({std::cos(a1), std::sin(a1)});
    }
    return triangles;
}

void float_attribute(GLuint index, int components, GLsizei stride, std::size_t offset,
                     GLuint divisor = 0) {
    glEnableVertexAttribArray(index);
    glVertexAttribPointer(index, components, GL_FLOAT, GL_FALSE, stride,
                          reinterpret_cast<const void*>(offset));
    glVertexAttribDivisor(index, divisor);
}

template <typename T>
void upload(GLuint buffer, const std::vector<T>& data) {
    glBindBuffer(GL_ARRAY_BUFFER, buffer);
    // Orphan and refill: the driver need not wait for the previous draw from this buffer.
    glBufferData(GL_ARRAY_BUFFER, static_cast<GLsizeiptr>(data.size() * sizeof(T)), data.data(),
                 GL_STREAM_DRAW);
}

struct MarkerInstance {
    glm::vec3 position;
    glm::vec4 color;
    float size_px;
};

}  // namespace

struct Renderer::Gl {
    ShaderProgram box{"box.vert", "box.frag"};
    ShaderProgram line{"line.vert", "flat.frag", "line.geom"};
    ShaderProgram flat{"flat.vert", "flat.frag"};
    ShaderProgram marker{"marker.vert", "flat.frag"};
    ShaderProgram background{"background.vert", "background.frag"};

    GLuint box_vao = 0, cube_vbo = 0, instance_vbo = 0;
    GLuint line_vao = 0, line_vbo = 0;
    GLuint flat_vao = 0, flat_vbo = 0;
    GLuint marker_vao = 0, star_vbo = 0, marker_vbo = 0;
    GLuint empty_vao = 0;
    std::array<GLint, 2> shape_first{};  // indexed by MarkerShape
    std::array<GLsizei, 2> shape_count{};
    std::vector<BoxInstance> sorted;   // scratch: translucent boxes back to front
    std::vector<BoxInstance> visible;  // scratch: boxes with at least one face to draw

    Gl() {
        const auto cube = unit_cube();
        glGenVertexArrays(1, &box_vao);
        glGenBuffers(1, &cube_vbo);
        glGenBuffers(1, &instance_vbo);
        glBindVertexArray(box_vao);
        glBindBuffer(GL_ARRAY_BUFFER, cube_vbo);
        glBufferData(GL_ARRAY_BUFFER, static_cast<GLsizeiptr>(cube.size() * sizeof(CubeVertex)),
                     cube.data(), GL_STATIC_DRAW);
        float_attribute(0, 3, sizeof(CubeVertex), offsetof(CubeVertex, corner));
        float_attribute(1, 3, sizeof(CubeVertex), offsetof(CubeVertex, normal));
        glBindBuffer(GL_ARRAY_BUFFER, instance_vbo);
        constexpr GLsizei stride = sizeof(BoxInstance);
        float_attribute(2, 3, stride, offsetof(BoxInstance, centre), 1);
        float_attribute(3, 4, stride, offsetof(BoxInstance, orientation), 1);
        float_attribute(4, 3, stride, offsetof(BoxInstance, size), 1);
        float_attribute(5, 4, stride, offsetof(BoxInstance, color), 1);
        float_attribute(6, 1, stride, offsetof(BoxInstance, flags), 1);
        float_attribute(7, 1, stride, offsetof(BoxInstance, faces), 1);

        glGenVertexArrays(1, &line_vao);
        glGenBuffers(1, &line_vbo);
        glBindVertexArray(line_vao);
        glBindBuffer(GL_ARRAY_BUFFER, line_vbo);
        float_attribute(0, 3, sizeof(LineVertex), offsetof(LineVertex, position));
        float_attribute(1, 4, sizeof(LineVertex), offsetof(LineVertex, color));
        float_attribute(2, 1, sizeof(LineVertex), offsetof(LineVertex, width_px));

        glGenVertexArrays(1, &flat_vao);
        glGenBuffers(1, &flat_vbo);
        glBindVertexArray(flat_vao);
        glBindBuffer(GL_ARRAY_BUFFER, flat_vbo);
        float_attribute(0, 3, sizeof(TriangleVertex), offsetof(TriangleVertex, position));
        float_attribute(1, 4, sizeof(TriangleVertex), offsetof(TriangleVertex, color));

        // All marker shapes in one buffer: shape k is vertices [shape_first[k], +shape_count[k]).
        auto star = star_triangles();
        const auto dot = dot_triangles();
        shape_first = {0, static_cast<GLint>(star.size())};
        shape_count = {static_cast<GLsizei>(star.size()), static_cast<GLsizei>(dot.size())};
        star.insert(star.end(), dot.begin(), dot.end());
        glGenVertexArrays(1, &marker_vao);
        glGenBuffers(1, &star_vbo);
        glGenBuffers(1, &marker_vbo);
        glBindVertexArray(marker_vao);
        glBindBuffer(GL_ARRAY_BUFFER, star_vbo);
        glBufferData(GL_ARRAY_BUFFER, static_cast<GLsizeiptr>(star.size() * sizeof(glm::vec2)),
                     star.data(), GL_STATIC_DRAW);
        float_attribute(0, 2, sizeof(glm::vec2), 0);
        glBindBuffer(GL_ARRAY_BUFFER, marker_vbo);
        float_attribute(1, 3, sizeof(MarkerInstance), offsetof(MarkerInstance, position), 1);
        float_attribute(2, 4, sizeof(MarkerInstance), offsetof(MarkerInstance, color), 1);
        float_attribute(3, 1, sizeof(MarkerInstance), offsetof(MarkerInstance, size_px), 1);

        // Core profile needs a bound VAO even for attribute-less draws (the background).
        glGenVertexArrays(1, &empty_vao);
        glBindVertexArray(0);
        check_gl_error("creating the renderer's buffers");
    }

    ~Gl() {
        const GLuint arrays[] = {box_vao, line_vao, flat_vao, marker_vao, empty_vao};
        const GLuint buffers[] = {cube_vbo, instance_vbo, line_vbo, flat_vbo, star_vbo, marker_vbo};
        glDeleteVertexArrays(5, arrays);
        glDeleteBuffers(6, buffers);
    }

    void draw_boxes(const std::vector<BoxInstance>& boxes) {
        // Voxels with every face hidden cost vertex work only: leave them out.
        visible.clear();
        for (const auto& b : boxes)
            if (b.faces > 0.5f) visible.push_back(b);
        if (visible.empty()) return;
        glBindVertexArray(box_vao);
        upload(instance_vbo, visible);
        glDrawArraysInstanced(GL_TRIANGLES, 0, 36, static_cast<GLsizei>(visible.size()));
    }

    void draw_lines(const std::vector<LineVertex>& lines) {
        if (lines.size() < 2) return;
        glBindVertexArray(line_vao);
        upload(line_vbo, lines);
        glDrawArrays(GL_LINES, 0, static_cast<GLsizei>(lines.size() / 2 * 2));
    }

    void draw_triangles(const std::vector<TriangleVertex>& triangles) {
        if (triangles.size() < 3) return;
        glBindVertexArray(flat_vao);
        upload(flat_vbo, triangles);
        glDrawArrays(GL_TRIANGLES, 0, static_cast<GLsizei>(triangles.size() / 3 * 3));
    }
};

Renderer::Renderer(RenderStyle style) : gl_(std::make_unique<Gl>()), style_(style) {}

Renderer::~Renderer() = default;

void Renderer::draw(const DrawList& list, const Camera& camera, int width_px, int height_px) {
    Gl& gl = *gl_;
    const int w = std::max(width_px, 1), h = std::max(height_px, 1);
    const float aspect = static_cast<float>(w) / static_cast<float>(h);
    const glm::mat4 view_proj = camera.view_projection(aspect);
    const glm::vec2 viewport{static_cast<float>(w), static_cast<float>(h)};
    const glm::vec3 forward = camera.forward();

    glViewport(0, 0, w, h);
    glDisable(GL_BLEND);
    glDepthMask(GL_TRUE);
    glClearColor(style_.background_bottom.r, style_.background_bottom.g, style_.background_bottom.b,
                 1.0f);
    glClear(GL_COLOR_BUFFER_BIT | GL_DEPTH_BUFFER_BIT);

    // Background gradient, no depth.
    glDisable(GL_DEPTH_TEST);
    glDisable(GL_CULL_FACE);
    gl.background.use();
    gl.background.set("u_top", style_.background_top);
    gl.background.set("u_bottom", style_.background_bottom);
    glBindVertexArray(gl.empty_vao);
    glDrawArrays(GL_TRIANGLES, 0, 3);

    glEnable(GL_DEPTH_TEST);
    glDepthFunc(GL_LEQUAL);

    // Floor, pushed back in depth so the grid lines on it and voxels resting on it win.
    gl.flat.use();
    gl.flat.set("u_view_proj", view_proj);
    glEnable(GL_POLYGON_OFFSET_FILL);
    glPolygonOffset(2.0f, 2.0f);
    gl.draw_triangles(list.floor);
    glDisable(GL_POLYGON_OFFSET_FILL);
    // The grid writes no depth: lines drawn later on the floor (workspace box) cover it cleanly.
    glDepthMask(GL_FALSE);
    gl.line.use();
    gl.line.set("u_view_proj", view_proj);
    gl.line.set("u_viewport_px", viewport);
    gl.draw_lines(list.floor_lines);
    glDepthMask(GL_TRUE);

    // Opaque voxels.
    glEnable(GL_CULL_FACE);
    glCullFace(GL_BACK);
    // The key light comes from above the viewer's left shoulder, whatever the view.
    const glm::vec3 light = glm::normalize(-0.45f * camera.right() + 0.70f * camera.up() -
                                           0.55f * forward + glm::vec3(0.0f, 0.0f, 0.35f));
    gl.box.use();
    gl.box.set("u_view_proj", view_proj);
    gl.box.set("u_light_dir", light);
    gl.box.set("u_view_dir", -forward);
    gl.box.set("u_edge_px", style_.edge_half_width_px);
    gl.draw_boxes(list.boxes);

    // Lines (grid, workspace box, face outlines, trail), pulled slightly toward the eye so
    // edges that lie on voxel faces stay visible.
    glDisable(GL_CULL_FACE);
    glEnable(GL_POLYGON_OFFSET_FILL);
    glPolygonOffset(-1.0f, -2.0f);
    gl.line.use();
    gl.line.set("u_view_proj", view_proj);
    gl.line.set("u_viewport_px", viewport);
    gl.draw_lines(list.lines);
    glDisable(GL_POLYGON_OFFSET_FILL);

    // Translucent pass: no depth writes, back to front. Boundary faces (quads of six vertices)
    // behind the workspace centre go first, then translucent voxels by depth, then nearer faces.
    glEnable(GL_BLEND);
    glBlendFuncSeparate(GL_SRC_ALPHA, GL_ONE_MINUS_SRC_ALPHA, GL_ONE, GL_ONE_MINUS_SRC_ALPHA);
    glDepthMask(GL_FALSE);
    const float middle = glm::dot(list.workspace_bounds.centre(), forward);
    std::vector<TriangleVertex> far_faces, near_faces;
    for (std::size_t i = 0; i + 5 < list.translucent_triangles.size(); i += 6) {
        const auto& t = list.translucent_triangles;
        // A plane seen face-on would veil the whole picture: its outline (a line) is enough.
        const glm::vec3 normal =
            glm::cross(t[i + 1].position - t[i].position, t[i + 2].position - t[i].position);
        const float length = glm::length(normal);
        if (length > 0.0f && std::fabs(glm::dot(normal / length, forward)) > 0.97f) continue;
        glm::vec3 centroid(0.0f);
        for (std::size_t k = 0; k < 6; ++k)
            centroid += t[i + k].position;
        auto& out = glm::dot(centroid / 6.0f, forward) > middle ? far_faces : near_faces;
        out.insert(out.end(), list.translucent_triangles.begin() + static_cast<std::ptrdiff_t>(i),
                   list.translucent_triangles.begin() + static_cast<std::ptrdiff_t>(i + 6));
    }
    gl.flat.use();
    gl.draw_triangles(far_faces);
    if (!list.translucent_boxes.empty()) {
        gl.sorted = list.translucent_boxes;
        std::sort(gl.sorted.begin(), gl.sorted.end(),
                  [&](const BoxInstance& a, const BoxInstance& b) {
                      return glm::dot(a.centre, forward) > glm::dot(b.centre, forward);
                  });
        glEnable(GL_CULL_FACE);
        gl.box.use();
        gl.draw_boxes(gl.sorted);
        glDisable(GL_CULL_FACE);
    }
    gl.flat.use();
    gl.draw_triangles(near_faces);
    glDepthMask(GL_TRUE);

    // Lines and markers over everything. Markers: a dark rim, then the fill, per shape.
    glDisable(GL_DEPTH_TEST);
    gl.line.use();
    gl.draw_lines(list.lines_on_top);
    if (!list.markers.empty()) {
        // Sizes are given for a 720-pixel-high picture and follow the picture's height.
        const float scale = std::clamp(static_cast<float>(h) / 720.0f, 0.6f, 2.0f);
        gl.marker.use();
        gl.marker.set("u_view_proj", view_proj);
        gl.marker.set("u_viewport_px", viewport);
        glBindVertexArray(gl.marker_vao);
        for (std::size_t shape = 0; shape < gl.shape_first.size(); ++shape) {
            std::vector<MarkerInstance> instances;
            for (int pass = 0; pass < 2; ++pass)
                for (const auto& m : list.markers) {
                    if (static_cast<std::size_t>(m.shape) != shape) continue;
                    if (pass == 0)
                        instances.push_back({m.position, glm::vec4(0.25f, 0.18f, 0.02f, 1.0f),
                                             scale * m.size_px + 2.5f});
                    else
                        instances.push_back({m.position, m.color, scale * m.size_px});
                }
            if (instances.empty()) continue;
            upload(gl.marker_vbo, instances);
            glDrawArraysInstanced(GL_TRIANGLES, gl.shape_first[shape], gl.shape_count[shape],
                                  static_cast<GLsizei>(instances.size()));
        }
    }

    // Screen-space overlay in pixels.
    const Overlay overlay = build_overlay(list, camera, w, h);
    const glm::mat4 pixels = glm::ortho(0.0f, viewport.x, 0.0f, viewport.y, -1.0f, 1.0f);
    gl.flat.use();
    gl.flat.set("u_view_proj", pixels);
    gl.draw_triangles(overlay.triangles);
    gl.line.use();
    gl.line.set("u_view_proj", pixels);
    gl.draw_lines(overlay.lines);

    glDisable(GL_BLEND);
    glEnable(GL_DEPTH_TEST);
    glBindVertexArray(0);
    if (style_.check_errors) check_gl_error("Renderer::draw");
}

}  // namespace bhm::render
