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

VplSampler::VplSampler(const Scene& scene) : mScene(&scene) {
    for (const Material& m : scene.materials) mMaterials.push_back(toGpuMaterial(m));
}

std::vector<shader::BidirVpl> VplSampler::sample(std::uint64_t first, std::uint32_t count, std::uint32_t seed,
                                                 double time, float lift) {
    if (!mEmbree || mEmbree->time() != time) {
        mEmbree = std::make_unique<EmbreeScene>(*mScene, time);
    }
    const std::vector<Light> lights = mScene->lightsAt(time);
    std::vector<shader::BidirVpl> out(count);
    if (lights.empty()) {
        return out; // all invalid: the mode's plan skips VPLs without point/spot lights
    }
    const float selectPdf = 1.0f / float(lights.size());
    for (std::uint32_t k = 0; k < count; ++k) {
        shader::BidirVpl& v = out[k];
        const std::uint64_t pair = first + k;
        const std::uint32_t key = shader::blHash(seed ^ kVplStreamKey) ^ shader::blHash(std::uint32_t(pair >> 32));
        const std::uint32_t index = static_cast<std::uint32_t>(pair);
        const float uLight = shader::blHashRandom(key, 3 * index);
        const glm::vec2 u(shader::blHashRandom(key, 3 * index + 1), shader::blHashRandom(key, 3 * index + 2));
        const auto l = std::min<std::size_t>(static_cast<std::size_t>(uLight * float(lights.size())), lights.size() - 1);
        const shader::GpuLight light = toGpuLight(lights[l]);
        const glm::vec3 omega =
            light.type == shader::kLightSpot ? sampleSpot(u, light) : shader::blSampleUniformSphere(u);
        v.light = static_cast<std::uint32_t>(l);
        v.pdfLight = selectPdf * shader::blBidirEmissionPdf(light, omega);
        v.intensity = light.intensity * shader::blLightProfile(light, omega);
        SurfaceHit hit;
        if (!(v.pdfLight > 0.0f) || !mEmbree->intersectFromLight(light.position, omega, hit)) {
            continue; // escaped: a sample of zero
        }
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
        // Textured albedo at VPLs: not yet (the material's; BidirMode.h says so).
        v.albedo = mMaterials[material].albedo;
        v.toLight = toLight;
        v.areaPdf = v.pdfLight * std::max(cosine, 0.0f) / (hit.t * hit.t);
        v.cubeCentre = hit.position + ng * lift;
        const glm::vec3 reflectance = v.albedo + mMaterials[material].specular;
        v.valid = cosine > 0.0f && reflectance != glm::vec3(0.0f) && v.intensity != glm::vec3(0.0f) ? 1u : 0u;
    }
    return out;
}

} // namespace bl
