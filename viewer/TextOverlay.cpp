#include "viewer/TextOverlay.h"

#include <algorithm>
#include <vector>

#include <stb/stb_easy_font.h>

namespace bl::viewer {

namespace {

void fill(Rgba8Image& f, int x0, int y0, int x1, int y1, unsigned char value) {
    x0 = std::max(x0, 0), y0 = std::max(y0, 0), x1 = std::min(x1, f.width), y1 = std::min(y1, f.height);
    for (int y = y0; y < y1; ++y) {
        for (int x = x0; x < x1; ++x) {
            unsigned char* o = f.texels.data() + (std::size_t(y) * f.width + x) * 4;
            o[0] = o[1] = o[2] = value;
        }
    }
}

struct Vertex {
    float x, y, z;
    unsigned char rgba[4];
};

} // namespace

void drawText(Rgba8Image& frame, int x, int y, const std::string& text, int scale) {
    std::string line;
    int row = 0;
    auto flush = [&]() {
        if (!line.empty()) {
            static std::vector<Vertex> vertices(4 * 4096);
            std::vector<char> buffer(line.begin(), line.end());
            buffer.push_back('\0');
            const int quads = stb_easy_font_print(0.0f, 0.0f, buffer.data(), nullptr, vertices.data(),
                                                  int(vertices.size() * sizeof(Vertex)));
            const int top = y + row * 12 * scale;
            // A dark backing one font unit wider than the glyphs, then the glyphs in white.
            for (int pass = 0; pass < 2; ++pass) {
                for (int q = 0; q < quads; ++q) {
                    const Vertex* v = &vertices[std::size_t(q) * 4];
                    const int x0 = x + int(v[0].x) * scale, y0 = top + int(v[0].y) * scale;
                    const int x1 = x + int(v[2].x) * scale, y1 = top + int(v[2].y) * scale;
                    if (pass == 0) fill(frame, x0 - scale, y0 - scale, x1 + scale, y1 + scale, 0);
                    else fill(frame, x0, y0, x1, y1, 255);
                }
            }
        }
        line.clear();
        ++row;
    };
    for (char c : text) {
        if (c == '\n') flush();
        else line += c;
    }
    flush();
}

} // namespace bl::viewer
