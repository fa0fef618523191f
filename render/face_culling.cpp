#include "render/face_culling.hpp"

#include <array>

#include <glm/glm.hpp>

namespace bhm::render {

namespace {

bool opaque(const BoxInstance& box) {
    return box.color.a >= 0.999f;
}

// Do face +axis of a and face -axis of b coincide (within tolerance, metres)?
bool faces_meet(const BoxInstance& a, const BoxInstance& b, int axis, float tolerance) {
    const float tolerance2 = tolerance * tolerance;
    const int t1 = (axis + 1) % 3, t2 = (axis + 2) % 3;
    for (int corner = 0; corner < 4; ++corner) {
        std::array<int, 3> sa{}, sb{};
        sa[axis] = 1;
        sb[axis] = -1;
        sa[t1] = sb[t1] = (corner & 1) ? 1 : -1;
        sa[t2] = sb[t2] = (corner & 2) ? 1 : -1;
        const glm::vec3 d = box_corner(a, sa[0], sa[1], sa[2]) - box_corner(b, sb[0], sb[1], sb[2]);
        if (glm::dot(d, d) > tolerance2) return false;
    }
    return true;
}

}  // namespace

glm::vec3 rotate_vector(const glm::vec4& q, const glm::vec3& v) {
    // v' = q v q*, expanded; q.x is the scalar part.
    const glm::vec3 u{q.y, q.z, q.w};
    return v + 2.0f * glm::cross(u, glm::cross(u, v) + q.x * v);
}

glm::vec3 box_corner(const BoxInstance& box, int sx, int sy, int sz) {
    const glm::vec3 local = 0.5f * glm::vec3(sx, sy, sz) * box.size;
    return box.centre + rotate_vector(box.orientation, local);
}

void cull_hidden_faces(const BodyView& body, std::vector<BoxInstance>& boxes,
                       float meet_tolerance) {
    const long long cells = static_cast<long long>(body.nx) * body.ny * body.nz;
    if (cells <= 0 || boxes.empty()) return;
    std::vector<int> box_in_cell(static_cast<std::size_t>(cells), -1);
    for (std::size_t i = 0; i < boxes.size(); ++i) {
        const int v = static_cast<int>(boxes[i].voxel);
        if (v < 0 || v >= body.voxel_count()) continue;
        box_in_cell[static_cast<std::size_t>(body.voxel_cell[static_cast<std::size_t>(v)])] =
            static_cast<int>(i);
    }
    const float tolerance = meet_tolerance * static_cast<float>(body.voxel_size_m);
    const int stride[3] = {1, body.nx, body.nx * body.ny};
    const int extent[3] = {body.nx, body.ny, body.nz};
    for (std::size_t i = 0; i < boxes.size(); ++i) {
        BoxInstance& box = boxes[i];
        const int v = static_cast<int>(box.voxel);
        if (v < 0 || v >= body.voxel_count()) continue;
        const int cell = body.voxel_cell[static_cast<std::size_t>(v)];
        const auto coords = body.voxel_coords(v);
        std::array<int, 6> neighbour{};
        bool enclosed = opaque(box);
        for (int face = 0; face < 6; ++face) {
            const int axis = face / 2, step = (face % 2) ? 1 : -1;
            const int c = coords[static_cast<std::size_t>(axis)] + step;
            neighbour[static_cast<std::size_t>(face)] =
                (c < 0 || c >= extent[axis])
                    ? -1
                    : box_in_cell[static_cast<std::size_t>(cell + step * stride[axis])];
            const int n = neighbour[static_cast<std::size_t>(face)];
            enclosed = enclosed && n >= 0 && opaque(boxes[static_cast<std::size_t>(n)]);
        }
        std::uint32_t faces = 0;
        if (!enclosed) {
            for (int face = 0; face < 6; ++face) {
                const int n = neighbour[static_cast<std::size_t>(face)];
                bool hidden = false;
                if (n >= 0) {
                    const BoxInstance& other = boxes[static_cast<std::size_t>(n)];
                    if (opaque(other) || !opaque(box)) {
                        const int axis = face / 2;
                        hidden = (face % 2) ? faces_meet(box, other, axis, tolerance)
                                            : faces_meet(other, box, axis, tolerance);
                    }
                }
                if (!hidden) faces |= 1u << face;
            }
        }
        box.faces = static_cast<float>(faces);
    }
}

}  // namespace bhm::render
