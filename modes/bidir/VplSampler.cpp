#include "modes/bidir/VplSampler.h"

#include "scene/ShaderConversions.h"

#include <cmath>
#include <limits>
#include <shared/Frame.h>
#include <shared/Lights.h>
#include <shared/Random.h>
#include <shared/Sampling.h>

namespace bl {

namespace {
// Decorrelates the VPL stream from the camera's pixel streams, which use the same hash of the run
// seed (any odd constant far from small pixel indices works).
constexpr std::uint32_t kVplStreamKey = 0x85ebca6bu;
// The area source's x0: numbers of their own, so the point lights' streams stay as they were.
constexpr std::uint32_t kAreaStreamKey = 0x3c6ef372u;

// A direction with density proportional to the spot light's profile (blBidirEmissionPdf): the CDF
// over cos(theta) from the axis outward inverted for one number, so stratified inputs stay
// stratified. Mass of the inner cone a = 1 - cosInner, of the smoothstep band b = (cosInner -
// cosOuter) / 2; in the band, with x = (cos - cosOuter) / (cosInner - cosOuter), the mass beyond x
// toward the axis is (1/2 - x^3 + x^4 / 2) (cosInner - cosOuter), monotone: solved by bisection.
glm::vec3 sampleSpot(glm::vec2 u, const shader::GpuLight& light) {
    const double cosInner = light.cosInner, cosOuter = light.cosOuter;
    const double a = 1.0 - cosInner, width = cosInner - cosOuter;
    const double s = double(u.x) * (a + 0.5 * width);
    double z = 0.0;
    if (s < a) {
        z = 1.0 - s;
    } else {
        const double q = 0.5 - (s - a) / width; // x^3 - x^4 / 2 = q, in [0, 1/2]
        double lo = 0.0, hi = 1.0;
        for (int i = 0; i < 40; ++i) {
            const double mid = 0.5 * (lo + hi);
            (mid * mid * mid * (1.0 - 0.5 * mid) < q ? lo : hi) = mid;
        }
        z = cosOuter + 0.5 * (lo + hi) * width;
    }
    const double r = std::sqrt(std::max(0.0, 1.0 - z * z));
    const double phi = 2.0 * 3.14159265358979323846 * double(u.y);
    glm::vec3 t, b;
    shader::blOrthonormalBasis(light.direction, t, b);
    return glm::normalize(float(r * std::cos(phi)) * t + float(r * std::sin(phi)) * b + float(z) * light.direction);
}
} // namespace

VplSampler::VplSampler(const Scene& scene, bool areaSource)
    : mScene(&scene), mAlbedo(scene), mEmitters(scene), mAreaSource(areaSource && !mEmitters.empty()) {
    for (const Material& m : scene.materials) mMaterials.push_back(toGpuMaterial(m));
}

void VplSampler::bake(double time) {
    if (!mEmbree || mEmbree->time() != time) {
        mEmbree = std::make_unique<EmbreeScene>(*mScene, time);
    }
}

std::vector<shader::BidirVpl> VplSampler::sample(std::uint64_t first, std::uint32_t count, std::uint32_t seed,
                                                 double time, float lift) {
    bake(time);
    const std::vector<Light> lights = mScene->lightsAt(time);
    std::vector<shader::BidirVpl> out(count);
    const std::size_t sources = lights.size() + (areaSource() ? 1u : 0u);
    if (sources == 0) {
        return out; // all invalid: the mode's plan skips VPLs without lights
    }
    const float selectPdf = 1.0f / float(sources);
    for (std::uint32_t k = 0; k < count; ++k) {
        shader::BidirVpl& v = out[k];
        const std::uint64_t pair = first + k;
        const std::uint32_t key = pairKey(seed, pair);
        const std::uint32_t index = static_cast<std::uint32_t>(pair);
        const float uLight = shader::blHashRandom(key, 3 * index);
        const auto l = std::min<std::size_t>(static_cast<std::size_t>(uLight * float(sources)), sources - 1);
        if (l == lights.size()) {
            v = areaVpl(pair, seed, time, lift);
            continue;
        }
        const glm::vec2 u(shader::blHashRandom(key, 3 * index + 1), shader::blHashRandom(key, 3 * index + 2));
        const shader::GpuLight light = toGpuLight(lights[l]);
        const glm::vec3 omega =
            light.type == shader::kLightSpot ? sampleSpot(u, light) : shader::blSampleUniformSphere(u);
        v.light = static_cast<std::uint32_t>(l);
        v.pdfLight = selectPdf * shader::blBidirEmissionPdf(light, omega);
        v.intensity = light.intensity * shader::blLightProfile(light, omega);
        SurfaceHit hit;
        if (v.pdfLight > 0.0f && mEmbree->intersectFromLight(light.position, omega, hit)) {
            landed(v, omega, hit, lift);
        } // else escaped: a sample of zero
    }
    return out;
}

shader::BidirVpl VplSampler::areaVpl(std::uint64_t pair, std::uint32_t seed, double time, float lift) {
    bake(time);
    shader::BidirVpl v{};
    const std::size_t lights = mScene->lightsAt(time).size();
    v.light = static_cast<std::uint32_t>(lights);
    if (!areaSource()) {
        return v;
    }
    const float selectPdf = 1.0f / float(lights + 1); // the source: one among the L lights and the area one
    const std::uint32_t key = pairKey(seed, pair);
    const std::uint32_t index = static_cast<std::uint32_t>(pair);
    // x0 from numbers of a stream of its own (the point lights' streams stay as they were), the
    // direction from the pair's own two.
    const std::uint32_t areaKey = shader::blHash(key ^ kAreaStreamKey);
    float coordinateScale = 0.0f; // the triangle's: the ray's offset off it (EmbreeScene::offsetOrigin)
    const shader::GpuEmitterPoint x0 = mEmitters.point(
        shader::blHashRandom(areaKey, 3 * index),
        {shader::blHashRandom(areaKey, 3 * index + 1), shader::blHashRandom(areaKey, 3 * index + 2)}, time, 0.0f,
        &coordinateScale);
    const glm::vec2 u(shader::blHashRandom(key, 3 * index + 1), shader::blHashRandom(key, 3 * index + 2));
    glm::vec3 t, b;
    shader::blOrthonormalBasis(x0.normal, t, b);
    const glm::vec3 local = shader::blSampleCosineHemisphere(u);
    const glm::vec3 omega = glm::normalize(local.x * t + local.y * b + local.z * x0.normal);
    const float cos0 = glm::dot(omega, x0.normal);
    v.pdfLight = selectPdf * cos0 * shader::kInvPi;
    v.intensity = x0.emission * (x0.areaPdf > 0.0f ? cos0 / x0.areaPdf : 0.0f);
    SurfaceHit hit;
    if (v.pdfLight > 0.0f && mEmbree->intersect(EmbreeScene::offsetOrigin(x0.position, x0.normal, coordinateScale), omega,
                                                std::numeric_limits<float>::infinity(), hit)) {
        landed(v, omega, hit, lift);
    } // else escaped: a sample of zero
    return v;
}

std::uint32_t VplSampler::pairKey(std::uint32_t seed, std::uint64_t pair) {
    return shader::blHash(seed ^ kVplStreamKey) ^ shader::blHash(std::uint32_t(pair >> 32));
}

void VplSampler::landed(shader::BidirVpl& v, const glm::vec3& omega, const SurfaceHit& hit, float lift) const {
    // Two-sided reflection, as the reference shades: the side the light ray arrives from.
    const bool frontFacing = glm::dot(hit.geometricNormal, omega) < 0.0f;
    const glm::vec3 ng = frontFacing ? hit.geometricNormal : -hit.geometricNormal;
    const glm::vec3 ns = frontFacing ? hit.shadingNormal : -hit.shadingNormal;
    const std::uint32_t material = mScene->meshes[hit.mesh].material;
    const glm::vec3 toLight = -omega;
    const float cosine = glm::dot(ns, toLight);
    v.position = hit.position;
    v.normal = ns;
    v.material = material;
    v.albedo = mAlbedo.at(material, hit.uv);
    v.toLight = toLight;
    v.areaPdf = v.pdfLight * std::max(cosine, 0.0f) / (hit.t * hit.t);
    v.cubeCentre = hit.position + ng * lift;
    const glm::vec3 reflectance = v.albedo + mMaterials[material].specular;
    v.valid = cosine > 0.0f && reflectance != glm::vec3(0.0f) && v.intensity != glm::vec3(0.0f) ? 1u : 0u;
}

} // namespace bl
