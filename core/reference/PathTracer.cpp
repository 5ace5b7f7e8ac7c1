#include "reference/PathTracer.h"

#include "image/BilinearLookup.h"
#include "scene/ShaderConversions.h"

#include <cmath>
#include <cstdio>
#include <limits>
#include <shared/BrdfSampling.h>
#include <shared/Camera.h>
#include <shared/Lights.h>
#include <shared/Random.h>

namespace bl {

namespace {

// Russian roulette keeps a path with probability min(kMaxSurvival, max throughput): capped below 1
// so that a path of unit throughput still ends in a closed furnace.
constexpr float kMaxSurvival = 0.95f;

std::string describe(const glm::vec3& v) {
    char buf[96];
    std::snprintf(buf, sizeof(buf), "(%.6g, %.6g, %.6g)", v.x, v.y, v.z);
    return buf;
}

} // namespace

glm::vec3 PathSample::total() const {
    glm::vec3 t(0.0f);
    for (const glm::vec3& l : layers) t += l;
    return t;
}

bool PathSample::finite() const {
    // The total too: finite layers can still overflow when summed.
    glm::vec3 t = total();
    return std::isfinite(t.x) && std::isfinite(t.y) && std::isfinite(t.z);
}

PathTracer::PathTracer(const EmbreeScene& geometry, const LightSampler& lights, const EnvironmentLight& environment,
                       const std::vector<Image>& linearTextures, const shader::GpuCamera& camera,
                       PathTracerSettings settings)
    : mGeometry(&geometry), mLights(&lights), mEnvironment(&environment), mTextures(&linearTextures),
      mCamera(camera), mSettings(settings) {
    for (const Material& m : geometry.scene().materials) {
        mMaterials.push_back(toGpuMaterial(m));
    }
    for (const Light& l : geometry.scene().lightsAt(geometry.time())) {
        mDeltaLights.push_back(toGpuLight(l));
    }
}

glm::vec3 PathTracer::albedoAt(const Material& m, glm::vec2 uv) const {
    if (m.albedoTexture < 0) {
        return m.albedo;
    }
    // OBJ texture coordinates have v = 0 at the bottom; image row 0 is the top.
    return bilinearLookup((*mTextures)[static_cast<std::size_t>(m.albedoTexture)], {uv.x, 1.0f - uv.y}, Wrap::Repeat,
                          Wrap::Repeat);
}

PathSample PathTracer::trace(int x, int y, std::uint32_t sampleIndex, std::uint32_t seed,
                             std::vector<std::string>* log) const {
    const auto width = static_cast<std::uint32_t>(mCamera.width);
    shader::RandomStream rng = shader::blRandomStream(seed, static_cast<std::uint32_t>(y) * width + x, sampleIndex);
    const glm::vec2 pixel = glm::vec2(x, y) + shader::blRandom2(rng);
    return tracePath(mCamera.position, shader::blCameraRayDirection(mCamera, pixel), rng, nullptr, log);
}

PathSample PathTracer::traceLeaving(const SurfaceHit& at, bool back, std::uint32_t index, std::uint32_t sampleIndex,
                                    std::uint32_t seed) const {
    shader::RandomStream rng = shader::blRandomStream(seed, index, sampleIndex);
    const glm::vec3 normal = back ? -at.geometricNormal : at.geometricNormal;
    return tracePath(at.position, -normal, rng, &at, nullptr);
}

PathSample PathTracer::tracePath(glm::vec3 origin, glm::vec3 direction, shader::RandomStream& rng,
                                 const SurfaceHit* first, std::vector<std::string>* log) const {
    const Scene& scene = mGeometry->scene();
    PathSample out;
    auto add = [&](int segments, const glm::vec3& value) {
        out.layers[std::min(segments, kPathLayerCount) - 1] += value;
        if (log) log->push_back("  + " + describe(value) + " at path length " + std::to_string(segments));
    };

    glm::vec3 throughput(1.0f);
    float lastBrdfPdf = 0.0f; // density of the direction just sampled (0: camera ray)
    glm::vec3 lastPosition = origin;
    const float infinity = std::numeric_limits<float>::infinity();

    for (int segments = 1;; ++segments) {
        SurfaceHit hit;
        const bool given = segments == 1 && first;
        if (given) {
            hit = *first;
        } else {
            ++out.rays;
        }
        if (!given && !mGeometry->intersect(origin, direction, infinity, hit)) {
            if (mEnvironment->present()) {
                glm::vec3 le = mEnvironment->radiance(direction);
                float w = segments == 1 ? 1.0f : shader::blPowerHeuristic(lastBrdfPdf, mLights->pdfEnvironment(direction));
                add(segments, throughput * le * w);
            }
            if (log) log->push_back("segment " + std::to_string(segments) + ": escaped along " + describe(direction));
            break;
        }
        const Mesh& mesh = scene.meshes[hit.mesh];
        if (log) {
            log->push_back("segment " + std::to_string(segments) + ": hit " + mesh.name + " triangle " +
                           std::to_string(hit.triangle) + " at " + describe(hit.position) + ", throughput " +
                           describe(throughput));
        }
        const bool frontFacing = glm::dot(hit.geometricNormal, direction) < 0.0f;
        if (mesh.emissive() && frontFacing) {
            float w = 1.0f;
            if (segments > 1) {
                float pdfLight = mLights->pdfEmitter(hit.mesh, hit.triangle, lastPosition, hit.position, hit.geometricNormal);
                w = shader::blPowerHeuristic(lastBrdfPdf, pdfLight);
            }
            add(segments, throughput * mesh.emission * w);
        }
        if (segments >= mSettings.maxSegments) {
            break;
        }

        // Two-sided reflection: shade on the side the path arrives from.
        const glm::vec3 wi = -direction;
        const float side = frontFacing ? 1.0f : -1.0f;
        const glm::vec3 ng = hit.geometricNormal * side;
        const glm::vec3 ns = hit.shadingNormal * side;
        const Material& material = scene.materials[mesh.material];
        const shader::GpuMaterial& m = mMaterials[mesh.material];
        const glm::vec3 albedo = albedoAt(material, hit.uv);
        const glm::vec3 p = hit.position;
        const glm::vec3 above = EmbreeScene::offsetOrigin(p, ng, hit.offsetScale);

        // Next-event estimation: every point/spot light, then one area or environment sample.
        for (const shader::GpuLight& light : mDeltaLights) {
            glm::vec3 d = light.position - p;
            float dist2 = glm::dot(d, d);
            float dist = std::sqrt(dist2);
            glm::vec3 wl = d / dist;
            float cosine = glm::dot(ns, wl);
            float profile = shader::blLightProfile(light, -wl);
            if (cosine <= 0.0f || glm::dot(ng, wl) <= 0.0f || profile <= 0.0f) continue;
            ++out.rays;
            if (mGeometry->occludedFromLight(above, light.position)) continue;
            glm::vec3 f = shader::blEvalBrdf(m, albedo, ns, wl, wi);
            add(segments + 1, throughput * f * light.intensity * (profile * cosine / dist2));
        }
        {
            float pick = shader::blRandom(rng);
            glm::vec2 point = shader::blRandom2(rng);
            LightSample ls = mLights->sample(p, glm::vec3(pick, point));
            float cosine = glm::dot(ns, ls.direction);
            if (ls.pdf > 0.0f && cosine > 0.0f && glm::dot(ng, ls.direction) > 0.0f) {
                bool blocked;
                ++out.rays;
                if (std::isinf(ls.distance)) {
                    blocked = mGeometry->occluded(above, ls.direction, infinity);
                } else {
                    glm::vec3 target = EmbreeScene::offsetOrigin(ls.point, -ls.direction, ls.offsetScale);
                    glm::vec3 toTarget = target - above;
                    float len = glm::length(toTarget);
                    blocked = !(len > 0.0f) || mGeometry->occluded(above, toTarget / len, len);
                }
                if (!blocked) {
                    glm::vec3 f = shader::blEvalBrdf(m, albedo, ns, ls.direction, wi);
                    float w = shader::blPowerHeuristic(ls.pdf, shader::blBrdfPdf(m, albedo, ns, wi, ls.direction));
                    add(segments + 1, throughput * f * ls.radiance * (cosine * w / ls.pdf));
                }
            }
        }

        // Continue by sampling the BRDF.
        float lobe = shader::blRandom(rng);
        glm::vec3 wo = shader::blSampleBrdf(m, albedo, ns, wi, glm::vec3(lobe, shader::blRandom2(rng)));
        float pdf = shader::blBrdfPdf(m, albedo, ns, wi, wo);
        float cosine = glm::dot(ns, wo);
        if (!(pdf > 0.0f) || cosine <= 0.0f || glm::dot(ng, wo) <= 0.0f) {
            break;
        }
        throughput *= shader::blEvalBrdf(m, albedo, ns, wi, wo) * (cosine / pdf);
        if (segments >= mSettings.rrDepth) {
            float survive = std::min(kMaxSurvival, std::max({throughput.x, throughput.y, throughput.z}));
            if (!(shader::blRandom(rng) < survive)) {
                break;
            }
            throughput /= survive;
        }
        lastBrdfPdf = pdf;
        lastPosition = p;
        origin = above;
        direction = wo;
    }
    return out;
}

} // namespace bl
