#version 330 core
// Widens a segment into a quad of constant pixel width (core profile has no wide lines), after
// clipping it to the near plane so segments that pass behind the eye stay correct.
layout(lines) in;
layout(triangle_strip, max_vertices = 4) out;

in vec4 g_color[];
in float g_width_px[];

uniform vec2 u_viewport_px;

out vec4 f_color;

vec4 clip_to_near(vec4 inside, vec4 outside) {
    // Near plane in clip space: z = -w.
    float a = inside.z + inside.w, b = outside.z + outside.w;
    return mix(inside, outside, a / (a - b));
}

void main() {
    vec4 p0 = gl_in[0].gl_Position, p1 = gl_in[1].gl_Position;
    bool in0 = p0.z >= -p0.w, in1 = p1.z >= -p1.w;
    if (!in0 && !in1) return;
    if (!in0) p0 = clip_to_near(p1, p0);
    if (!in1) p1 = clip_to_near(p0, p1);

    vec2 s0 = p0.xy / p0.w * 0.5 * u_viewport_px;
    vec2 s1 = p1.xy / p1.w * 0.5 * u_viewport_px;
    vec2 dir = s1 - s0;
    float len = length(dir);
    dir = len > 1e-4 ? dir / len : vec2(1.0, 0.0);
    vec2 normal = vec2(-dir.y, dir.x);

    vec4 ends[2] = vec4[2](p0, p1);
    for (int e = 0; e < 2; ++e) {
        float half_width = 0.5 * g_width_px[e];
        // Extend each end by half the width so joined segments meet without gaps.
        vec2 along = (e == 0 ? -dir : dir) * half_width;
        for (int side = -1; side <= 1; side += 2) {
            vec2 offset_px = along + float(side) * normal * half_width;
            vec4 p = ends[e];
            p.xy += offset_px / (0.5 * u_viewport_px) * p.w;
            gl_Position = p;
            f_color = g_color[e];
            EmitVertex();
        }
    }
    EndPrimitive();
}
