#version 330 core
// Instanced voxel boxes: a unit cube per instance, scaled along its own axes by the voxel's
// current size, rotated by its orientation quaternion, moved to its centre (engine::VoxelPoses).
layout(location = 0) in vec3 a_corner;  // unit cube corner, coordinates in {-0.5, 0.5}
layout(location = 1) in vec3 a_normal;  // outward face normal in the cube's own frame
layout(location = 2) in vec3 i_center;
layout(location = 3) in vec4 i_orientation;  // w, x, y, z
layout(location = 4) in vec3 i_size;
layout(location = 5) in vec4 i_color;
layout(location = 6) in float i_flags;
layout(location = 7) in float i_faces;  // bit f set: draw face f (x-, x+, y-, y+, z-, z+)

uniform mat4 u_view_proj;

out vec3 v_local;  // position on the unit cube, for the outlines and the hatch
out vec3 v_normal;
flat out vec3 v_face_axis;  // |a_normal|: which local axis the face is normal to
flat out vec4 v_color;
flat out int v_flags;

vec3 rotate(vec4 q, vec3 v) {
    // v' = q v q*, expanded (q.x is the scalar part).
    vec3 u = q.yzw;
    return v + 2.0 * cross(u, cross(u, v) + q.x * v);
}

void main() {
    // Which face this vertex belongs to, from its outward normal.
    vec3 a = abs(a_normal);
    int axis = a.x > 0.5 ? 0 : (a.y > 0.5 ? 1 : 2);
    int face = 2 * axis + (a_normal[axis] > 0.0 ? 1 : 0);
    if (((int(i_faces + 0.5) >> face) & 1) == 0) {
        // Hidden face (render/face_culling.cpp): outside the clip volume, so never rasterised.
        gl_Position = vec4(0.0, 0.0, -2.0, 1.0);
        v_local = vec3(0.0);
        v_normal = vec3(0.0, 0.0, 1.0);
        v_face_axis = vec3(0.0);
        v_color = vec4(0.0);
        v_flags = 0;
        return;
    }
    vec3 world = i_center + rotate(i_orientation, a_corner * i_size);
    gl_Position = u_view_proj * vec4(world, 1.0);
    v_local = a_corner;
    // Scaling along the box's own axes keeps face normals; only the rotation applies.
    v_normal = rotate(i_orientation, a_normal);
    v_face_axis = abs(a_normal);
    v_color = i_color;
    v_flags = int(i_flags + 0.5);
}
