#version 330 core
// Screen-facing symbols of constant pixel size (the star on the (0,0,0) voxel): the shape's
// 2D vertices are offset in pixels around the projected anchor point.
layout(location = 0) in vec2 a_offset;  // shape vertex, outer radius 1
layout(location = 1) in vec3 i_position;
layout(location = 2) in vec4 i_color;
layout(location = 3) in float i_size_px;

uniform mat4 u_view_proj;
uniform vec2 u_viewport_px;

out vec4 f_color;

void main() {
    vec4 p = u_view_proj * vec4(i_position, 1.0);
    p.xy += a_offset * i_size_px / (0.5 * u_viewport_px) * p.w;
    gl_Position = p;
    f_color = i_color;
}
