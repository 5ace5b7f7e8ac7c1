#include "atlas/TexelRadiance.h"

#include "base/Error.h"

namespace bl::atlas {

TexelRadiance TexelRadiance::like(const TexelMaps& maps) {
    TexelRadiance r;
    r.width = maps.width;
    r.height = maps.height;
    r.pages = maps.pages;
    const std::size_t n = maps.valid.size();
    r.side[0].assign(n, glm::vec3(0.0f));
    r.side[1].assign(n, glm::vec3(0.0f));
    r.valid.resize(n);
    for (std::size_t t = 0; t < n; ++t) r.valid[t] = maps.valid[t] == 1 ? 1 : 0;
    return r;
}

ImageMetrics texelMetrics(const TexelRadiance& test, const TexelRadiance& reference) {
    return texelMetrics(test, reference, std::vector<std::uint8_t>(test.texels(), 1));
}

ImageMetrics texelMetrics(const TexelRadiance& test, const TexelRadiance& reference,
                          const std::vector<std::uint8_t>& only) {
    if (only.size() != test.texels()) {
        throw Error("texel comparison: a mask of " + std::to_string(only.size()) + " entries for " +
                    std::to_string(test.texels()) + " texels");
    }
    if (test.width != reference.width || test.height != reference.height || test.pages != reference.pages ||
        test.valid != reference.valid) {
        throw Error("texel comparison: the two are not of the same atlas (" + std::to_string(test.width) + "x" +
                    std::to_string(test.height) + " x " + std::to_string(test.pages) + " against " +
                    std::to_string(reference.width) + "x" + std::to_string(reference.height) + " x " +
                    std::to_string(reference.pages) + " pages, or other texels)");
    }
    std::vector<glm::vec3> t, r;
    for (std::size_t i = 0; i < test.texels(); ++i) {
        if (!test.valid[i] || !only[i]) continue;
        for (int s = 0; s < 2; ++s) {
            const glm::vec3 a = test.side[s][i], b = reference.side[s][i];
            if (a == glm::vec3(0.0f) && b == glm::vec3(0.0f)) continue;
            t.push_back(a);
            r.push_back(b);
        }
    }
    if (t.empty()) {
        throw Error("texel comparison: no texel side is lit in either");
    }
    Image ti(static_cast<int>(t.size()), 1), ri(static_cast<int>(r.size()), 1);
    for (std::size_t i = 0; i < t.size(); ++i) {
        ti.at(static_cast<int>(i), 0) = t[i];
        ri.at(static_cast<int>(i), 0) = r[i];
    }
    MetricOptions options;
    options.blockSize = 1; // one row: blocks mean nothing here
    return computeMetrics(ti, ri, options);
}

std::vector<std::uint8_t> chartBorder(const TexelMaps& maps) {
    std::vector<std::uint8_t> border(maps.valid.size(), 0);
    const auto same = [&](std::size_t t, int x, int y, int page) {
        if (x < 0 || y < 0 || x >= maps.width || y >= maps.height) return false;
        const std::size_t n = (std::size_t(page) * maps.height + y) * maps.width + x;
        return maps.valid[n] == 1 && maps.chart[n] == maps.chart[t];
    };
    for (std::size_t t = 0; t < maps.valid.size(); ++t) {
        if (maps.valid[t] != 1) continue;
        const int x = int(t % maps.width), y = int((t / maps.width) % maps.height), page = int(t / maps.width / maps.height);
        border[t] = !(same(t, x - 1, y, page) && same(t, x + 1, y, page) && same(t, x, y - 1, page) &&
                      same(t, x, y + 1, page));
    }
    return border;
}

std::vector<std::pair<std::string, Image>> texelImages(const TexelRadiance& radiance) {
    std::vector<std::pair<std::string, Image>> out;
    const char* names[2] = {"front", "back"};
    for (int s = 0; s < 2; ++s) {
        Image image(radiance.width, radiance.height * radiance.pages);
        for (std::size_t i = 0; i < radiance.texels(); ++i) {
            image.at(static_cast<int>(i % radiance.width), static_cast<int>(i / radiance.width)) = radiance.side[s][i];
        }
        out.emplace_back(names[s], std::move(image));
    }
    return out;
}

} // namespace bl::atlas
