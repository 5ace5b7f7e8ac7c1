#include "modes/bidir/ReflectiveShadowMap.h"

#include "base/Error.h"
#include "scene/Camera.h"
#include "scene/ShaderConversions.h"
#include "vk/Commands.h"

#include <algorithm>
#include <cmath>
#include <cstring>
#include <modes/bidir/Rsm.h>
#include <modes/bidir/rsm_sample.comp.spv.h>
#include <shared/Lights.h>
#include <shared/Random.h>

namespace bl {

namespace {
// Decorrelates the RSM's VPL stream from the camera's pixel streams and from the jitter stream.
constexpr std::uint32_t kRsmStreamKey = 0x85ebca6bu;
constexpr std::uint32_t kJitterStreamKey = 0x27d4eb2fu;

// The largest profile over a texel's centre and four corners: the light's intensity there, up to
// its colour (shared by all directions). Zero only where the whole texel is dark but for a sliver.
float texelProfile(const shader::GpuLight& light, std::uint32_t face, std::uint32_t col, std::uint32_t row,
                   std::uint32_t n) {
    glm::vec3 r, u, f;
    shader::blCubeFaceBasis(face, r, u, f);
    float best = 0.0f;
    for (const glm::vec2 o : {glm::vec2(0.5f), glm::vec2(0.0f), glm::vec2(1.0f, 0.0f), glm::vec2(0.0f, 1.0f),
                              glm::vec2(1.0f)}) {
        const float x = 2.0f * (float(col) + o.x) / float(n) - 1.0f;
        const float y = 1.0f - 2.0f * (float(row) + o.y) / float(n);
        best = std::max(best, shader::blLightProfile(light, glm::normalize(f + x * r + y * u)));
    }
    return best;
}
} // namespace

ReflectiveShadowMap::ReflectiveShadowMap(const vk::Context& ctx, const gpu::GpuScene& scene, std::uint32_t resolution)
    : mCtx(&ctx), mScene(&scene), mResolution(resolution) {
    // Position, normal and albedo are what a VPL takes; the surface channel is left out.
    mFace = std::make_unique<gpu::GBufferPass>(ctx, scene, resolution, resolution, gpu::GBufferSurface::Unused);
    const std::size_t lights = std::max<std::size_t>(scene.scene().lights.size(), 1);
    const VkDeviceSize words = shader::kBidirRsmHeaderWords + lights * 6 * std::size_t(resolution) * resolution;
    mCdf = vk::Buffer(ctx, words * 4, VK_BUFFER_USAGE_STORAGE_BUFFER_BIT, vk::MemoryUse::Upload);
    for (const Material& m : scene.scene().materials) mMaterials.push_back(toGpuMaterial(m));

    VkDevice device = ctx.device();
    // Room for one VPL's texel until sample() asks for more.
    mCapacity = 1;
    mTexels = vk::Buffer(ctx, sizeof(shader::BidirRsmTexel), VK_BUFFER_USAGE_STORAGE_BUFFER_BIT, vk::MemoryUse::Readback);
    mBound = vk::BoundSet(
        device, {vk::Bound::storageImage(shader::kBidirRsmBindingPosition, mFace->attachment(shader::kGBufferPosition).view()),
                 vk::Bound::storageImage(shader::kBidirRsmBindingNormal, mFace->attachment(shader::kGBufferNormal).view()),
                 vk::Bound::storageImage(shader::kBidirRsmBindingAlbedo, mFace->attachment(shader::kGBufferAlbedo).view()),
                 vk::Bound::storageBuffer(shader::kBidirRsmBindingCdf, mCdf.get()),
                 vk::Bound::storageBuffer(shader::kBidirRsmBindingTexels, mTexels.get())});
    mSample = vk::ComputePass<shader::BidirRsmPush>(device, kSpv_modes_bidir_rsm_sample_comp, {mBound.layout()});
}

void ReflectiveShadowMap::buildCdf(const std::vector<shader::GpuLight>& lights) {
    const std::uint32_t n = mResolution;
    const std::size_t perLight = 6 * std::size_t(n) * n;
    mStart.assign(lights.size() * perLight, 0u);
    std::vector<double> weight(perLight);
    for (std::size_t l = 0; l < lights.size(); ++l) {
        double total = 0.0;
        for (std::uint32_t face = 0; face < 6; ++face) {
            for (std::uint32_t row = 0; row < n; ++row) {
                for (std::uint32_t col = 0; col < n; ++col) {
                    // Flux through the texel: I times its solid angle A / J at the centre.
                    const double x = 2.0 * (col + 0.5) / n - 1.0, y = 1.0 - 2.0 * (row + 0.5) / n;
                    const double j = 1.0 + x * x + y * y;
                    const std::size_t t = (std::size_t(face) * n + row) * n + col;
                    weight[t] = texelProfile(lights[l], face, col, row, n) / (j * std::sqrt(j));
                    total += weight[t];
                }
            }
        }
        if (!(total > 0.0)) {
            throw Error("bidir: light " + std::to_string(l) + " emits nothing its reflective shadow map can sample");
        }
        double cumulative = 0.0;
        for (std::size_t t = 0; t < perLight; ++t) {
            mStart[l * perLight + t] = static_cast<std::uint32_t>(std::min(std::floor(cumulative / total * 4294967296.0),
                                                                           4294967295.0));
            cumulative += weight[t];
        }
    }
    auto* words = static_cast<std::uint32_t*>(mCdf.data());
    std::memset(words, 0, shader::kBidirRsmHeaderWords * 4);
    words[0] = n;
    std::memcpy(words + shader::kBidirRsmHeaderWords, mStart.data(), mStart.size() * 4);
}

float ReflectiveShadowMap::directionPdf(std::uint32_t light, const glm::vec3& omega) const {
    float x = 0.0f, y = 0.0f;
    const std::uint32_t t = shader::blRsmTexelOf(omega, mResolution, x, y);
    const std::size_t perLight = 6 * std::size_t(mResolution) * mResolution;
    const std::size_t base = light * perLight;
    const std::uint32_t next = t + 1 < perLight ? mStart[base + t + 1] : 0u;
    return shader::blRsmDirectionPdf(mStart[base + t], next, x, y, mResolution);
}

std::vector<shader::BidirVpl> ReflectiveShadowMap::sample(std::uint64_t first, std::uint32_t count, std::uint32_t seed,
                                                          double time, float lift, vk::GpuTimer* timer,
                                                          bool areaSource, std::vector<std::uint32_t>& areaPairs) {
    std::vector<shader::BidirVpl> out(count);
    areaPairs.clear();
    const std::vector<Light> sceneLights = mScene->scene().lightsAt(time);
    if (sceneLights.empty() || count == 0) {
        return out;
    }
    std::vector<shader::GpuLight> lights;
    for (const Light& l : sceneLights) lights.push_back(toGpuLight(l));
    if (!mCdfTime || (mScene->features().animated && *mCdfTime != time)) {
        buildCdf(lights);
        mCdfTime = time;
    }
    if (count > mCapacity) {
        mCapacity = count;
        mTexels = vk::Buffer(*mCtx, sizeof(shader::BidirRsmTexel) * count, VK_BUFFER_USAGE_STORAGE_BUFFER_BIT,
                             vk::MemoryUse::Readback);
        mBound.rebind(shader::kBidirRsmBindingTexels, mTexels.get());
    }
    auto* texels = static_cast<shader::BidirRsmTexel*>(mTexels.data());
    std::memset(texels, 0, sizeof(shader::BidirRsmTexel) * count);

    const std::uint32_t n = mResolution;
    shader::BidirRsmPush push{};
    push.pairs = count;
    push.resolution = n;
    // The shader draws the source among lightCount: with the area source one more, which no
    // dispatch's light matches (its pairs stay unwritten).
    const auto sources = static_cast<std::uint32_t>(lights.size() + (areaSource ? 1u : 0u));
    push.lightCount = sources;
    push.key = shader::blHash(seed ^ kRsmStreamKey) ^ shader::blHash(std::uint32_t(first >> 32));
    push.first = static_cast<std::uint32_t>(first);
    const std::uint32_t jitterKey = shader::blHash(push.key ^ kJitterStreamKey) ^ shader::blHash(push.first);
    mCtx->submitAndWait([&](VkCommandBuffer cmd) {
        if (timer) timer->begin(cmd);
        const std::uint32_t scope = timer ? timer->start(cmd, "RSM cubes + VPL sampling") : 0;
        for (std::uint32_t l = 0; l < lights.size(); ++l) {
            for (std::uint32_t face = 0; face < 6; ++face) {
                glm::vec3 r, u, f;
                shader::blCubeFaceBasis(face, r, u, f);
                Camera camera;
                camera.pose.position = lights[l].position;
                // The target one scene radius out along f, not one unit: f is a coordinate axis, so
                // target - position keeps exactly f's direction, while position + f vanished in
                // float's spacing beyond 2^24 (scenes scaled by 1e5 and more: an empty RSM, every
                // VPL lost).
                camera.pose.target = lights[l].position + f * mScene->radius();
                camera.pose.up = u;
                camera.fovDegrees = 90.0f;
                camera.fovAxis = FovAxis::X;
                camera.resolution = {int(n), int(n)};
                // One uniform jitter per face and frame, in NDC units (2 / N per texel).
                const std::uint32_t j = 6 * l + face;
                const glm::vec2 jitter(shader::blHashRandom(jitterKey, 2 * j), shader::blHashRandom(jitterKey, 2 * j + 1));
                mFace->record(cmd, makeGpuCamera(camera, time, mScene->cameraNear()), (jitter - 0.5f) * (2.0f / float(n)),
                              time, nullptr);
                vk::memoryBarrier(cmd, VK_PIPELINE_STAGE_2_ALL_GRAPHICS_BIT, VK_PIPELINE_STAGE_2_COMPUTE_SHADER_BIT);
                push.light = l;
                push.face = face;
                mSample.dispatch(cmd, push, vk::groupCount(count, shader::kBidirRsmGroupSize), mBound.sets());
                vk::memoryBarrier(cmd, VK_PIPELINE_STAGE_2_COMPUTE_SHADER_BIT,
                                  VK_PIPELINE_STAGE_2_ALL_GRAPHICS_BIT | VK_PIPELINE_STAGE_2_HOST_BIT);
            }
        }
        if (timer) timer->stop(cmd, scope);
    });
    if (timer) timer->collect();

    const float selectPdf = 1.0f / float(sources);
    for (std::uint32_t k = 0; areaSource && k < count; ++k) {
        // rsm_sample.comp.glsl's draw of the source, on the host.
        const float u = float(shader::blRsmRandom(push.key, push.first + k, 0u) >> 8u) * (1.0f / 16777216.0f);
        if (std::min(std::uint32_t(u * float(sources)), sources - 1u) == lights.size()) areaPairs.push_back(k);
    }
    for (std::uint32_t k = 0; k < count; ++k) {
        const shader::BidirRsmTexel& texel = texels[k];
        shader::BidirVpl& v = out[k];
        if (texel.written == 0u || !(texel.position.w > 0.0f)) {
            continue; // the light ray escaped: a sample of zero
        }
        const shader::GpuLight& light = lights[texel.light];
        const glm::vec3 position(texel.position);
        const glm::vec3 d = position - light.position;
        const float r2 = glm::dot(d, d);
        if (!(r2 > 0.0f)) {
            continue;
        }
        const glm::vec3 omega = d / std::sqrt(r2);
        float x = 0.0f, y = 0.0f;
        if (shader::blRsmTexelOf(omega, n, x, y) != texel.texel) {
            ++mMismatches;
        }
        const glm::vec3 normal(texel.normal); // faces the light: the RSM's camera
        const auto material = static_cast<std::uint32_t>(texel.normal.w);
        const float cosine = glm::dot(normal, -omega);
        v.position = position;
        v.light = texel.light;
        v.normal = normal;
        v.material = material;
        v.albedo = glm::vec3(texel.albedo); // textured
        v.pdfLight = selectPdf * directionPdf(texel.light, omega);
        v.intensity = light.intensity * shader::blLightProfile(light, omega);
        v.toLight = -omega;
        v.areaPdf = v.pdfLight * std::max(cosine, 0.0f) / r2;
        v.cubeCentre = position + normal * lift;
        const glm::vec3 reflectance = v.albedo + mMaterials[material].specular;
        v.valid = cosine > 0.0f && v.pdfLight > 0.0f && reflectance != glm::vec3(0.0f) && v.intensity != glm::vec3(0.0f)
                      ? 1u
                      : 0u;
    }
    return out;
}

} // namespace bl
