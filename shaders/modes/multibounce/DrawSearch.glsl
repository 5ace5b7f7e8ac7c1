// Mode multibounce: which draw a global triangle index belongs to, by binary search of a table in
// GpuScene draw order (firstTriangle ascending). BL_DEFINE_DRAW_SEARCH(name, array) defines
// `uint name(uint t, uint count)`: the last entry of array[0, count) with firstTriangle <= t.
#ifndef BL_MULTIBOUNCE_DRAW_SEARCH_GLSL
#define BL_MULTIBOUNCE_DRAW_SEARCH_GLSL
#define BL_DEFINE_DRAW_SEARCH(name, array)                                                                \
    uint name(uint t, uint count) {                                                                   \
        uint lo = 0u, hi = count;                                                                     \
        while (hi - lo > 1u) {                                                                        \
            uint mid = (lo + hi) / 2u;                                                                \
            if (array[mid].firstTriangle <= t) {                                                      \
                lo = mid;                                                                             \
            } else {                                                                                  \
                hi = mid;                                                                             \
            }                                                                                         \
        }                                                                                             \
        return lo;                                                                                    \
    }
#endif
