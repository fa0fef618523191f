#version 330 core
// One triangle that covers the viewport, no vertex buffer needed.
out float v_height;

void main() {
    vec2 p = vec2(float((gl_VertexID & 1) * 4 - 1), float((gl_VertexID & 2) * 2 - 1));
    v_height = 0.5 * (p.y + 1.0);
    gl_Position = vec4(p, 1.0, 1.0);
}
