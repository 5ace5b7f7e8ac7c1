#include "support/BoxQueries.h"

namespace bl::test {

std::vector<BoxPoint> boxPoints(int grid, int alongEdge, int acrossEdge, float band) {
    std::vector<BoxPoint> points;
    for (int axis = 0; axis < 3; ++axis) {
        for (int side = 0; side < 2; ++side) {
            const int u = (axis + 1) % 3, v = (axis + 2) % 3;
            auto add = [&](float a, float b) {
                glm::vec3 p(0.0f), n(0.0f);
                p[axis] = float(side);
                p[u] = a;
                p[v] = b;
                n[axis] = side == 0 ? -1.0f : 1.0f;
                points.push_back({p, n});
            };
            for (int i = 0; i < grid; ++i) {
                for (int j = 0; j < grid; ++j) add((i + 0.5f) / grid, (j + 0.5f) / grid);
            }
            for (int i = 0; i < alongEdge; ++i) {
                const float along = (i + 0.37f) / alongEdge;
                for (int j = 0; j < acrossEdge; ++j) {
                    const float across = band * (j + 0.5f) / acrossEdge;
                    add(across, along);
                    add(1.0f - across, along);
                    add(along, across);
                    add(along, 1.0f - across);
                }
            }
        }
    }
    return points;
}

} // namespace bl::test
