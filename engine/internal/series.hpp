#pragma once
// Private to the engine: two materials joined end to end (the two halves of a link, the two voxels
// of an edge spring) act as springs in series, each over half the length: 2 a b / (a + b).

namespace bhm::engine {

inline double series(double a, double b) {
    return 2.0 * a * b / (a + b);
}

}  // namespace bhm::engine
