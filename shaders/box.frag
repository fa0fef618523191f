#version 330 core
// Lit voxel faces with pixel-width outlines (so single voxels can be counted) and a hatch on
// held voxels. Outlines come from the distance to the face's edges in the cube's own
// coordinates, divided by its screen-space derivative: constant width at any zoom.
in vec3 v_local;
in vec3 v_normal;
flat in vec3 v_face_axis;
flat in vec4 v_color;
flat in int v_flags;

uniform vec3 u_light_dir;    // world, toward the light
uniform vec3 u_view_dir;     // world, toward the viewer
uniform float u_edge_px;     // outline half width in pixels

out vec4 frag_color;

const int kFixed = 1;
const int kGhost = 2;
const int kNoEdges = 4;
const vec3 kHatch = vec3(0.16, 0.62, 0.28);

float edge_distance_px(float coord) {
    return (0.5 - abs(coord)) / max(fwidth(coord), 1e-6);
}

void main() {
    vec3 n = normalize(v_normal);
    // Ambient + key light + a weak headlight, so all three visible face directions differ.
    float key = max(dot(n, u_light_dir), 0.0);
    float head = max(dot(n, u_view_dir), 0.0);
    vec3 base = v_color.rgb;

    // The two coordinates that run along this face.
    vec2 along = v_face_axis.x > 0.5 ? v_local.yz : (v_face_axis.y > 0.5 ? v_local.xz : v_local.xy);

    if ((v_flags & kFixed) != 0) {
        // Diagonal stripes, 4 per voxel edge, anti-aliased.
        float s = (along.x + along.y) * 4.0;
        float d = abs(fract(s) - 0.5);
        float w = fwidth(s);
        float stripe = 1.0 - smoothstep(0.16 - w, 0.16 + w, d);
        base = mix(base, kHatch, 0.9 * stripe);
    }

    vec3 color = base * (0.42 + 0.45 * key + 0.18 * head);
    float alpha = v_color.a;

    if ((v_flags & kNoEdges) == 0) {
        float d = min(edge_distance_px(along.x), edge_distance_px(along.y));
        float edge = 1.0 - smoothstep(u_edge_px - 0.5, u_edge_px + 0.5, d);
        bool ghost = (v_flags & kGhost) != 0;
        vec3 edge_color = ghost ? vec3(0.35, 0.37, 0.40) : base * 0.30;
        color = mix(color, edge_color, edge);
        if (ghost) alpha = mix(alpha, 0.55, edge);
    }
    frag_color = vec4(color, alpha);
}
