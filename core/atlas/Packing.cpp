#include "atlas/Packing.h"

#include <algorithm>
#include <atomic>
#include <tbb/blocked_range.h>
#include <tbb/combinable.h>
#include <tbb/parallel_for.h>
#include <cmath>
#include <limits>
#include <numeric>

namespace bl::atlas {

namespace {

float cross2(glm::vec2 o, glm::vec2 a, glm::vec2 b) { return (a.x - o.x) * (b.y - o.y) - (a.y - o.y) * (b.x - o.x); }

std::vector<glm::vec2> convexHull(std::vector<glm::vec2> p) {
    std::sort(p.begin(), p.end(), [](glm::vec2 a, glm::vec2 b) { return a.x < b.x || (a.x == b.x && a.y < b.y); });
    p.erase(std::unique(p.begin(), p.end()), p.end());
    if (p.size() < 3) return p;
    std::vector<glm::vec2> h(2 * p.size());
    std::size_t k = 0;
    for (std::size_t i = 0; i < p.size(); ++i) {
        while (k >= 2 && cross2(h[k - 2], h[k - 1], p[i]) <= 0) --k;
        h[k++] = p[i];
    }
    for (std::size_t i = p.size() - 1, t = k + 1; i > 0; --i) {
        while (k >= t && cross2(h[k - 2], h[k - 1], p[i - 1]) <= 0) --k;
        h[k++] = p[i - 1];
    }
    h.resize(k - 1);
    return h;
}

void bounds(const std::vector<glm::vec2>& p, glm::vec2& lo, glm::vec2& hi) {
    lo = glm::vec2(std::numeric_limits<float>::max());
    hi = glm::vec2(std::numeric_limits<float>::lowest());
    for (const glm::vec2& q : p) {
        lo = glm::min(lo, q);
        hi = glm::max(hi, q);
    }
}

// Columns tried per chart width when placing a chart: 1 for charts under this width, coarser above.
constexpr int kColumnSteps = 16;

} // namespace

void orientCharts(std::vector<FlatChart>& charts) {
    for (FlatChart& c : charts) {
        std::vector<glm::vec2> hull = convexHull(c.uv);
        float bestAngle = 0.0f, bestArea = std::numeric_limits<float>::max();
        for (std::size_t i = 0; i < hull.size(); ++i) {
            glm::vec2 e = hull[(i + 1) % hull.size()] - hull[i];
            if (glm::dot(e, e) == 0.0f) continue;
            const float angle = -std::atan2(e.y, e.x);
            const float cs = std::cos(angle), sn = std::sin(angle);
            glm::vec2 lo(std::numeric_limits<float>::max()), hi(std::numeric_limits<float>::lowest());
            for (const glm::vec2& q : hull) {
                glm::vec2 r(cs * q.x - sn * q.y, sn * q.x + cs * q.y);
                lo = glm::min(lo, r);
                hi = glm::max(hi, r);
            }
            const float area = (hi.x - lo.x) * (hi.y - lo.y);
            if (area < bestArea) {
                bestArea = area;
                bestAngle = angle;
            }
        }
        const float cs = std::cos(bestAngle), sn = std::sin(bestAngle);
        for (glm::vec2& q : c.uv) q = glm::vec2(cs * q.x - sn * q.y, sn * q.x + cs * q.y);
        glm::vec2 lo, hi;
        bounds(c.uv, lo, hi);
        if (hi.y - lo.y > hi.x - lo.x) {
            for (glm::vec2& q : c.uv) q = glm::vec2(q.y, -q.x); // a quarter turn keeps orientation
            bounds(c.uv, lo, hi);
        }
        for (glm::vec2& q : c.uv) q -= lo; // origin at the bounding rectangle's corner
    }
}

std::size_t TexelMask::texels() const {
    std::size_t n = 0;
    for (auto [lo, hi] : runs) n += std::size_t(hi - lo);
    return n;
}

TexelMask rasterizeMask(const std::vector<glm::vec2>& corners) {
    // A texel touching a triangle only along its boundary still counts, as in the coverage test;
    // widening every boundary a little keeps that true under float rounding of the placement.
    constexpr float kTouch = 1e-3f;
    struct Span {
        int x, lo, hi;
    };
    std::vector<Span> spans;
    for (std::size_t i = 0; i + 2 < corners.size(); i += 3) {
        const glm::vec2 t[3] = {corners[i], corners[i + 1], corners[i + 2]};
        const float minX = std::min(t[0].x, std::min(t[1].x, t[2].x)), maxX = std::max(t[0].x, std::max(t[1].x, t[2].x));
        for (int x = int(std::floor(minX - kTouch)); x <= int(std::floor(maxX + kTouch)); ++x) {
            // The triangle cut to the column's slab is convex: its rows run from the lowest to the
            // highest of its corners inside the slab and its edges' crossings of the slab's sides.
            const float side[2] = {float(x) - kTouch, float(x + 1) + kTouch};
            float lo = std::numeric_limits<float>::max(), hi = std::numeric_limits<float>::lowest();
            for (int k = 0; k < 3; ++k) {
                const glm::vec2 a = t[k], b = t[(k + 1) % 3];
                if (a.x >= side[0] && a.x <= side[1]) {
                    lo = std::min(lo, a.y);
                    hi = std::max(hi, a.y);
                }
                if (a.x == b.x) continue;
                for (float sx : side) {
                    if ((sx - a.x) * (sx - b.x) > 0.0f) continue;
                    const float y = a.y + (sx - a.x) / (b.x - a.x) * (b.y - a.y);
                    lo = std::min(lo, y);
                    hi = std::max(hi, y);
                }
            }
            if (lo > hi) continue;
            spans.push_back({x, int(std::floor(lo - kTouch)), int(std::floor(hi + kTouch)) + 1});
        }
    }
    TexelMask m;
    if (spans.empty()) return m;
    std::sort(spans.begin(), spans.end(), [](const Span& a, const Span& b) { return a.x < b.x || (a.x == b.x && a.lo < b.lo); });
    m.x0 = spans.front().x;
    m.width = spans.back().x - m.x0 + 1;
    m.columnStart.assign(std::size_t(m.width) + 1, 0);
    int yLo = std::numeric_limits<int>::max(), yHi = std::numeric_limits<int>::lowest();
    for (std::size_t i = 0; i < spans.size();) {
        const int x = spans[i].x;
        std::size_t columnBegin = m.runs.size();
        for (; i < spans.size() && spans[i].x == x; ++i) {
            if (m.runs.size() > columnBegin && m.runs.back().second >= spans[i].lo) {
                m.runs.back().second = std::max(m.runs.back().second, spans[i].hi);
            } else {
                m.runs.emplace_back(spans[i].lo, spans[i].hi);
            }
        }
        yLo = std::min(yLo, m.runs[columnBegin].first);
        for (std::size_t r = columnBegin; r < m.runs.size(); ++r) yHi = std::max(yHi, m.runs[r].second);
        m.columnStart[std::size_t(x - m.x0) + 1] = int(m.runs.size());
    }
    // Columns without spans (none inside a chart, but possible for scattered triangles) repeat
    // their predecessor's end.
    for (std::size_t c = 1; c < m.columnStart.size(); ++c) m.columnStart[c] = std::max(m.columnStart[c], m.columnStart[c - 1]);
    m.y0 = yLo;
    m.height = yHi - yLo;
    return m;
}

glm::vec2 turnChart(glm::vec2 q, int turns, glm::vec2 extent) {
    switch (turns & 3) {
    case 1: return {extent.y - q.y, q.x};
    case 2: return extent - q;
    case 3: return {q.y, extent.x - q.x};
    default: return q;
    }
}

namespace {

// Occupied row intervals [first, second) of one atlas column, sorted and disjoint.
using Column = std::vector<std::pair<int, int>>;

// The first occupied interval of `column` that meets rows [lo, hi), or nullptr.
const std::pair<int, int>* conflict(const Column& column, int lo, int hi) {
    auto it = std::upper_bound(column.begin(), column.end(), lo,
                               [](int v, const std::pair<int, int>& iv) { return v < iv.second; });
    return it != column.end() && it->first < hi ? &*it : nullptr;
}

void occupyRows(Column& column, int lo, int hi) { // rows [lo, hi)
    auto it = std::lower_bound(column.begin(), column.end(), std::make_pair(lo, lo));
    // Merge with overlapping or touching neighbours.
    if (it != column.begin() && std::prev(it)->second >= lo) --it;
    int a = lo, b = hi;
    auto first = it;
    while (it != column.end() && it->first <= b) {
        a = std::min(a, it->first);
        b = std::max(b, it->second);
        ++it;
    }
    it = column.erase(first, it);
    column.insert(it, {a, b});
}

} // namespace

ChartPacker::ChartPacker(int width, int height, int padding)
    : mWidth(width), mHeight(height), mPadding(padding), mColumns(std::size_t(width)) {}

void ChartPacker::take(const TexelMask& m, int dx, int dy) {
    for (int c = 0; c < m.width; ++c) {
        const int column = m.x0 + c + dx;
        for (int r = m.columnStart[c]; r < m.columnStart[c + 1]; ++r) {
            const int lo = std::max(0, m.runs[r].first + dy - mPadding);
            const int hi = std::min(mHeight, m.runs[r].second + dy + mPadding);
            for (int x = std::max(0, column - mPadding); x <= std::min(mWidth - 1, column + mPadding); ++x) {
                occupyRows(mColumns[x], lo, hi);
            }
        }
    }
    mUsedHeight = std::max(mUsedHeight, m.y0 + dy + m.height);
}

void ChartPacker::occupy(const FlatChart& placed) { take(rasterizeMask(placed.uv), 0, 0); }

namespace {

// A placement found by the search: the lowest top wins, ties go to the first turn and column.
struct Candidate {
    int top = std::numeric_limits<int>::max();
    int turn = -1, dx = 0, dy = 0;
    bool operator<(const Candidate& o) const {
        return top != o.top ? top < o.top : (turn != o.turn ? turn < o.turn : dx < o.dx);
    }
};

} // namespace

bool ChartPacker::place(const FlatChart& chart, float density, glm::vec2& offset, int& turns) {
    glm::vec2 lo, extent;
    bounds(chart.uv, lo, extent);
    TexelMask masks[4];
    std::vector<glm::vec2> corners(chart.uv.size());
    for (int turn = 0; turn < 4; ++turn) {
        // uv 0 lands on texel centre 0.5; placements then shift by whole texels.
        for (std::size_t k = 0; k < corners.size(); ++k) corners[k] = turnChart(chart.uv[k], turn, extent) * density + 0.5f;
        masks[turn] = rasterizeMask(corners);
    }
    // Columns are searched in parallel. A column's climb stops once its top exceeds the best top
    // found so far (ties are still climbed), so the choice does not depend on the threads' timing.
    std::atomic<int> bestTop{mHeight};
    tbb::combinable<Candidate> best;
    for (int turn = 0; turn < 4; ++turn) {
        const TexelMask& m = masks[turn];
        if (m.width > mWidth || m.height > mHeight) continue;
        // Wide charts try every 1/kColumnSteps of their width: the search stays affordable.
        const int step = std::max(1, m.width / kColumnSteps);
        const int positions = (mWidth - m.width) / step + 1;
        tbb::parallel_for(tbb::blocked_range<int>(0, positions, 16), [&](const tbb::blocked_range<int>& range) {
            Candidate& mine = best.local();
            for (int i = range.begin(); i != range.end(); ++i) {
                const int dx = i * step - m.x0;
                int dy = -m.y0;
                bool moved = true;
                while (moved && m.y0 + dy + m.height <= bestTop.load(std::memory_order_relaxed)) {
                    moved = false;
                    for (int c = 0; c < m.width && m.y0 + dy + m.height <= bestTop.load(std::memory_order_relaxed); ++c) {
                        const Column& column = mColumns[std::size_t(m.x0 + c + dx)];
                        for (int r = m.columnStart[c]; r < m.columnStart[c + 1]; ++r) {
                            const auto [runLo, runHi] = m.runs[r];
                            if (const auto* iv = conflict(column, runLo + dy, runHi + dy)) {
                                dy = iv->second - runLo;
                                moved = true;
                            }
                        }
                    }
                }
                const Candidate here{m.y0 + dy + m.height, turn, dx, dy};
                if (moved || here.top > bestTop.load(std::memory_order_relaxed)) continue;
                if (here < mine) mine = here;
                for (int seen = bestTop.load(); here.top < seen && !bestTop.compare_exchange_weak(seen, here.top);) {
                }
            }
        });
    }
    const Candidate chosen = best.combine([](const Candidate& a, const Candidate& b) { return a < b ? a : b; });
    if (chosen.turn < 0) return false;
    offset = glm::vec2(float(chosen.dx) + 0.5f, float(chosen.dy) + 0.5f);
    turns = chosen.turn;
    take(masks[chosen.turn], chosen.dx, chosen.dy);
    return true;
}

std::size_t ChartPacker::occupiedTexels() const {
    std::size_t n = 0;
    for (const Column& column : mColumns) {
        for (auto [lo, hi] : column) n += std::size_t(hi - lo);
    }
    return n;
}

bool packCharts(const std::vector<FlatChart>& charts, float density, int width, int height, int padding, int maxPages,
                Packing& out) {
    std::vector<double> area(charts.size(), 0.0);
    for (std::size_t i = 0; i < charts.size(); ++i) {
        glm::vec2 lo, hi;
        bounds(charts[i].uv, lo, hi);
        area[i] = double(hi.x) * hi.y;
    }
    std::vector<std::size_t> order(charts.size());
    std::iota(order.begin(), order.end(), 0);
    std::sort(order.begin(), order.end(), [&](std::size_t a, std::size_t b) { return area[a] > area[b]; });
    out.offsets.assign(charts.size(), glm::vec2(0.0f));
    out.turns.assign(charts.size(), 0);
    out.pages.assign(charts.size(), 0);
    std::vector<ChartPacker> pages;
    for (std::size_t i : order) {
        int page = 0;
        while (page < int(pages.size()) && !pages[std::size_t(page)].place(charts[i], density, out.offsets[i], out.turns[i])) ++page;
        if (page == int(pages.size())) {
            // A fresh page: if the chart does not fit there, it fits nowhere.
            if (page == maxPages) return false;
            pages.emplace_back(width, height, padding);
            if (!pages.back().place(charts[i], density, out.offsets[i], out.turns[i])) return false;
        }
        out.pages[i] = page;
    }
    out.pageCount = int(pages.size());
    out.usedHeight = pages.empty() ? 0 : pages.back().usedHeight();
    return true;
}

void placeChart(FlatChart& chart, float density, glm::vec2 offset, int turns) {
    glm::vec2 extent(0.0f);
    for (const glm::vec2& q : chart.uv) extent = glm::max(extent, q);
    for (glm::vec2& q : chart.uv) q = turnChart(q, turns, extent) * density + offset;
}

} // namespace bl::atlas
