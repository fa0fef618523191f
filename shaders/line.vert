#version 330 core
// Line vertices; line.geom widens each segment into a screen-space quad.
layout(location = 0) in vec3 a_position;
layout(location = 1) in vec4 a_color;
layout(location = 2) in float a_width_px;

uniform mat4 u_view_proj;

out vec4 g_color;
out float g_width_px;

void main() {
    gl_Position = u_view_proj * vec4(a_position, 1.0);
    g_color = a_color;
    g_width_px = a_width_px;
}
