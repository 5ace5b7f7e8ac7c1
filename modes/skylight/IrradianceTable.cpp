#include "modes/skylight/IrradianceTable.h"

#include <algorithm>
#include <cmath>
#include <modes/skylight/SkylightShared.h>
#include <shared/EnvMap.h>
#include <thread>

namespace bl {

static_assert(IrradianceTable::kWidth == int(shader::kSkylightIrradianceWidth) &&
              IrradianceTable::kHeight == int(shader::kSkylightIrradianceHeight));

namespace {

// Quadrature points of the map: direction and radiance times solid angle, as arrays (the sum over
// them vectorises).
struct Quadrature {
    std::vector<float> x, y, z, r, g, b;
};

// Points of `block` x `block` texels each, at the block's centre direction.
Quadrature quadrature(const Environment& env, int block) {
    const Image& map = env.map;
    const int w = map.width() / block, h = map.height() / block;
    const float rotation = glm::radians(env.rotationDegrees);
    Quadrature q;
    const std::size_t n = std::size_t(w) * h;
    for (auto* v : {&q.x, &q.y, &q.z, &q.r, &q.g, &q.b}) v->reserve(n);
    const double texelPhi = 2.0 * shader::kPi / map.width();
    for (int by = 0; by < h; ++by) {
        for (int bx = 0; bx < w; ++bx) {
            glm::dvec3 sum(0.0);
            for (int ty = by * block; ty < (by + 1) * block; ++ty) {
                // Exact solid angle of a lat-long texel row: dphi (cos theta0 - cos theta1).
                const double omega = texelPhi * (std::cos(shader::kPi * double(ty) / map.height()) -
                                                 std::cos(shader::kPi * double(ty + 1) / map.height()));
                for (int tx = bx * block; tx < (bx + 1) * block; ++tx) sum += glm::dvec3(map.at(tx, ty)) * omega;
            }
            const glm::vec3 d = shader::blEnvUvToDirection(glm::vec2((bx + 0.5f) / w, (by + 0.5f) / h), rotation);
            q.x.push_back(d.x);
            q.y.push_back(d.y);
            q.z.push_back(d.z);
            q.r.push_back(float(sum.x * env.scale));
            q.g.push_back(float(sum.y * env.scale));
            q.b.push_back(float(sum.z * env.scale));
        }
    }
    return q;
}

// Sum of max(0, n.d) L dOmega over the points: float partial sums in kLanes independent lanes
// (so the compiler vectorises without reassociating), per 256 points, double across.
glm::vec3 integrate(const Quadrature& q, const glm::vec3& n) {
    constexpr std::size_t kLanes = 8, kChunk = 256;
    glm::dvec3 total(0.0);
    const std::size_t count = q.x.size();
    for (std::size_t start = 0; start < count; start += kChunk) {
        const std::size_t end = std::min(count, start + kChunk);
        float r[kLanes] = {}, g[kLanes] = {}, b[kLanes] = {};
        std::size_t i = start;
        for (; i + kLanes <= end; i += kLanes) {
            for (std::size_t l = 0; l < kLanes; ++l) {
                const float c = std::max(0.0f, n.x * q.x[i + l] + n.y * q.y[i + l] + n.z * q.z[i + l]);
                r[l] += c * q.r[i + l];
                g[l] += c * q.g[i + l];
                b[l] += c * q.b[i + l];
            }
        }
        for (; i < end; ++i) {
            const float c = std::max(0.0f, n.x * q.x[i] + n.y * q.y[i] + n.z * q.z[i]);
            r[0] += c * q.r[i];
            g[0] += c * q.g[i];
            b[0] += c * q.b[i];
        }
        for (std::size_t l = 0; l < kLanes; ++l) total += glm::dvec3(r[l], g[l], b[l]);
    }
    return glm::vec3(total);
}

glm::vec3 tableNormal(int i, int j) {
    return shader::blEnvUvToDirection(
        glm::vec2(float(i) / IrradianceTable::kWidth, float(j) / (IrradianceTable::kHeight - 1)), 0.0f);
}

} // namespace

IrradianceTable::IrradianceTable(const Environment& env) {
    mEntries.assign(std::size_t(kWidth) * kHeight, glm::vec4(0.0f));
    if (!env.present) {
        return;
    }
    if (!env.hasMap()) {
        // A constant sky: E = pi L for every normal.
        std::fill(mEntries.begin(), mEntries.end(), glm::vec4(shader::kPi * env.radiance * env.scale, 0.0f));
        return;
    }
    const int block = std::size_t(env.map.width()) * env.map.height() > kQuadraturePoints &&
                              env.map.width() % 2 == 0 && env.map.height() % 2 == 0
                          ? 2
                          : 1;
    const Quadrature q = quadrature(env, block);
    const unsigned threads = std::max(1u, std::min(8u, std::thread::hardware_concurrency()));
    std::vector<std::thread> workers;
    for (unsigned t = 0; t < threads; ++t) {
        workers.emplace_back([&, t] {
            for (int j = int(t); j < kHeight; j += int(threads)) {
                for (int i = 0; i < kWidth; ++i) {
                    mEntries[std::size_t(j) * kWidth + i] = glm::vec4(integrate(q, tableNormal(i, j)), 0.0f);
                }
            }
        });
    }
    for (std::thread& w : workers) w.join();
}

glm::vec3 IrradianceTable::lookup(const glm::vec3& n) const {
    // As visibility.comp.glsl's blSkylightIrradiance.
    glm::vec2 t;
    const glm::uvec4 i = shader::blSkylightIrradianceTaps(n, t);
    auto at = [&](std::uint32_t index) { return glm::vec3(mEntries[index]); };
    return glm::mix(glm::mix(at(i.x), at(i.y), t.x), glm::mix(at(i.z), at(i.w), t.x), t.y);
}

std::vector<glm::vec3> IrradianceTable::bruteForce(const Environment& env, const std::vector<glm::vec3>& normals) {
    std::vector<glm::vec3> out;
    if (!env.hasMap()) {
        out.assign(normals.size(), env.present ? shader::kPi * env.radiance * env.scale : glm::vec3(0.0f));
        return out;
    }
    const Quadrature q = quadrature(env, 1);
    for (const glm::vec3& n : normals) out.push_back(integrate(q, n));
    return out;
}

} // namespace bl
