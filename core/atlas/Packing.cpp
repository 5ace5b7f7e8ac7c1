#include "atlas/Packing.h"

#include <algorithm>
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

namespace {

// A chart's outline at a density: per texel column, the lowest and highest texel row its
// triangles' bounding boxes reach (-1: none).
struct Outline {
    int width = 0;
    int height = 0;
    std::vector<int> bottom, top;
};

Outline outline(const FlatChart& c, float density, int turns, glm::vec2 extent) {
    Outline o;
    const glm::vec2 size = (turns % 2) ? glm::vec2(extent.y, extent.x) : extent;
    // The chart spans [0.5, 0.5 + size * density] in texels: the texels floor(0.5 + size * density)
    // + 1 wide and tall.
    o.width = int(std::floor(size.x * density + 0.5f)) + 1;
    o.height = int(std::floor(size.y * density + 0.5f)) + 1;
    o.bottom.assign(o.width, std::numeric_limits<int>::max());
    o.top.assign(o.width, -1);
    for (std::size_t i = 0; i < c.faces.size(); ++i) {
        glm::vec2 lo(std::numeric_limits<float>::max()), hi(std::numeric_limits<float>::lowest());
        for (int k = 0; k < 3; ++k) {
            glm::vec2 q = turnChart(c.uv[3 * i + k], turns, extent);
            // Same half-texel shift as the placement: uv 0 lands at texel 0.5.
            q = q * density + 0.5f;
            lo = glm::min(lo, q);
            hi = glm::max(hi, q);
        }
        const int x0 = std::max(0, int(std::floor(lo.x))), x1 = std::min(o.width - 1, int(std::floor(hi.x)));
        const int y0 = std::max(0, int(std::floor(lo.y))), y1 = std::min(o.height - 1, int(std::floor(hi.y)));
        for (int x = x0; x <= x1; ++x) {
            o.bottom[x] = std::min(o.bottom[x], y0);
            o.top[x] = std::max(o.top[x], y1);
        }
    }
    return o;
}

} // namespace

glm::vec2 turnChart(glm::vec2 q, int turns, glm::vec2 extent) {
    switch (turns & 3) {
    case 1: return {extent.y - q.y, q.x};
    case 2: return extent - q;
    case 3: return {q.y, extent.x - q.x};
    default: return q;
    }
}

bool packCharts(const std::vector<FlatChart>& charts, float density, int width, int height, int padding,
                std::vector<glm::vec2>& offsets, std::vector<int>& turns) {
    std::vector<glm::vec2> extent(charts.size());
    for (std::size_t i = 0; i < charts.size(); ++i) {
        glm::vec2 lo, hi;
        bounds(charts[i].uv, lo, hi);
        extent[i] = hi; // oriented charts start at the origin
    }
    std::vector<std::size_t> order(charts.size());
    std::iota(order.begin(), order.end(), 0);
    std::sort(order.begin(), order.end(), [&](std::size_t a, std::size_t b) {
        return extent[a].y > extent[b].y || (extent[a].y == extent[b].y && extent[a].x > extent[b].x);
    });
    offsets.assign(charts.size(), glm::vec2(0.0f));
    turns.assign(charts.size(), 0);
    std::vector<int> skyline(width, 0); // first free row of each column (padding included)
    for (std::size_t i : order) {
        int bestY = std::numeric_limits<int>::max(), bestX = -1;
        int bestTurn = 0;
        Outline best;
        for (int turn = 0; turn < 4; ++turn) {
            Outline o = outline(charts[i], density, turn, extent[i]);
            if (o.width > width) return false;
            // Drop the outline at every column; keep the placement whose top is lowest.
            for (int x = 0; x + o.width <= width; ++x) {
                int y = 0;
                for (int c = 0; c < o.width; ++c) {
                    if (o.top[c] >= 0) y = std::max(y, skyline[x + c] - o.bottom[c]);
                }
                const int top = y + o.height;
                if (top < bestY || (top == bestY && x < bestX)) {
                    bestY = top;
                    bestX = x;
                    bestTurn = turn;
                    best = o;
                }
            }
        }
        if (bestX < 0 || bestY > height) return false;
        const int y = bestY - best.height;
        offsets[i] = glm::vec2(float(bestX) + 0.5f, float(y) + 0.5f);
        turns[i] = bestTurn;
        // Raise the skyline over the chart's columns, grown by the padding on every side.
        for (int c = 0; c < best.width; ++c) {
            if (best.top[c] < 0) continue;
            const int raised = y + best.top[c] + 1 + padding;
            for (int x = std::max(0, bestX + c - padding); x <= std::min(width - 1, bestX + c + padding); ++x) {
                skyline[x] = std::max(skyline[x], raised);
            }
        }
    }
    return true;
}

namespace {

// Occupied row intervals [first, second) of one atlas column, sorted and disjoint.
using Column = std::vector<std::pair<int, int>>;

// The first occupied interval of `column` that meets rows [lo, hi], or nullptr.
const std::pair<int, int>* conflict(const Column& column, int lo, int hi) {
    auto it = std::upper_bound(column.begin(), column.end(), lo,
                               [](int v, const std::pair<int, int>& iv) { return v < iv.second; });
    return it != column.end() && it->first <= hi ? &*it : nullptr;
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

HoleFiller::HoleFiller(int width, int height, int padding)
    : mWidth(width), mHeight(height), mPadding(padding), mColumns(width) {}

void HoleFiller::occupy(const FlatChart& placed) {
    std::vector<int> bottom(mWidth, std::numeric_limits<int>::max()), top(mWidth, -1);
    for (std::size_t i = 0; i < placed.faces.size(); ++i) {
        glm::vec2 lo(std::numeric_limits<float>::max()), hi(std::numeric_limits<float>::lowest());
        for (int k = 0; k < 3; ++k) {
            lo = glm::min(lo, placed.uv[3 * i + k]);
            hi = glm::max(hi, placed.uv[3 * i + k]);
        }
        for (int x = std::max(0, int(std::floor(lo.x))); x <= std::min(mWidth - 1, int(std::floor(hi.x))); ++x) {
            bottom[x] = std::min(bottom[x], int(std::floor(lo.y)));
            top[x] = std::max(top[x], int(std::floor(hi.y)));
        }
    }
    for (int c = 0; c < mWidth; ++c) {
        if (top[c] < 0) continue;
        const int lo = std::max(0, bottom[c] - mPadding), hi = std::min(mHeight, top[c] + 1 + mPadding);
        for (int x = std::max(0, c - mPadding); x <= std::min(mWidth - 1, c + mPadding); ++x) occupyRows(mColumns[x], lo, hi);
    }
}

bool HoleFiller::place(const FlatChart& chart, float density, glm::vec2& offset, int& turns) {
    glm::vec2 lo, extent;
    bounds(chart.uv, lo, extent);
    int bestTop = std::numeric_limits<int>::max(), bestX = -1, bestY = 0, bestTurn = 0;
    Outline best;
    for (int turn = 0; turn < 4; ++turn) {
        Outline o = outline(chart, density, turn, extent);
        if (o.width > mWidth || o.height > mHeight) continue;
        // Large charts try every 1/16 of their width: the search stays affordable.
        const int step = std::max(1, o.width / 16);
        for (int x = 0; x + o.width <= mWidth; x += step) {
            int y = 0;
            bool moved = true;
            while (moved && y + o.height < bestTop) {
                moved = false;
                for (int c = 0; c < o.width; ++c) {
                    if (o.top[c] < 0) continue;
                    if (const auto* iv = conflict(mColumns[x + c], y + o.bottom[c], y + o.top[c])) {
                        y = iv->second - o.bottom[c];
                        moved = true;
                    }
                }
            }
            if (!moved && y + o.height <= mHeight && y + o.height < bestTop) {
                bestTop = y + o.height;
                bestX = x;
                bestY = y;
                bestTurn = turn;
                best = o;
            }
        }
    }
    if (bestX < 0) return false;
    offset = glm::vec2(float(bestX) + 0.5f, float(bestY) + 0.5f);
    turns = bestTurn;
    for (int c = 0; c < best.width; ++c) {
        if (best.top[c] < 0) continue;
        const int rowLo = std::max(0, bestY + best.bottom[c] - mPadding);
        const int rowHi = std::min(mHeight, bestY + best.top[c] + 1 + mPadding);
        for (int x = std::max(0, bestX + c - mPadding); x <= std::min(mWidth - 1, bestX + c + mPadding); ++x) {
            occupyRows(mColumns[x], rowLo, rowHi);
        }
    }
    return true;
}

bool packChartsFillingHoles(const std::vector<FlatChart>& charts, float density, int width, int height, int padding,
                            std::vector<glm::vec2>& offsets, std::vector<int>& turns) {
    std::vector<double> area(charts.size(), 0.0);
    for (std::size_t i = 0; i < charts.size(); ++i) {
        glm::vec2 lo, hi;
        bounds(charts[i].uv, lo, hi);
        area[i] = double(hi.x) * hi.y;
    }
    std::vector<std::size_t> order(charts.size());
    std::iota(order.begin(), order.end(), 0);
    std::sort(order.begin(), order.end(), [&](std::size_t a, std::size_t b) { return area[a] > area[b]; });
    offsets.assign(charts.size(), glm::vec2(0.0f));
    turns.assign(charts.size(), 0);
    HoleFiller filler(width, height, padding);
    for (std::size_t i : order) {
        if (!filler.place(charts[i], density, offsets[i], turns[i])) return false;
    }
    return true;
}

void placeChart(FlatChart& chart, float density, glm::vec2 offset, int turns) {
    glm::vec2 extent(0.0f);
    for (const glm::vec2& q : chart.uv) extent = glm::max(extent, q);
    for (glm::vec2& q : chart.uv) q = turnChart(q, turns, extent) * density + offset;
}

} // namespace bl::atlas
