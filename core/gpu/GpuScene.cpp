#include "gpu/GpuScene.h"

#include "base/Error.h"
#include "scene/ShaderConversions.h"

#include <algorithm>
#include <cmath>

namespace bl::gpu {

GpuScene::GpuScene(const vk::Context& ctx, const Scene& scene) : mScene(&scene), mFeatures(scene.features()) {
    mRadius = std::max(mFeatures.bounds.radius(), 1e-30f);
    std::vector<shader::GpuVertex> vertices;
    std::vector<std::uint32_t> indices;
    std::vector<glm::vec4> planes;
    for (std::uint32_t i = 0; i < scene.meshes.size(); ++i) {
        const Mesh& m = scene.meshes[i];
        GpuDraw d{i, static_cast<std::uint32_t>(indices.size()), static_cast<std::uint32_t>(m.triangles.size() * 3),
                  static_cast<std::int32_t>(vertices.size())};
        for (std::size_t v = 0; v < m.positions.size(); ++v) {
            glm::vec2 uv = m.uvs.empty() ? glm::vec2(0.0f) : m.uvs[v];
            vertices.push_back({glm::vec4(m.positions[v], uv.x), glm::vec4(m.normals[v], uv.y)});
        }
        for (const glm::uvec3& t : m.triangles) {
            indices.insert(indices.end(), {t.x, t.y, t.z});
            const glm::vec3& a = m.positions[t.x];
            glm::vec3 n = glm::normalize(glm::cross(m.positions[t.y] - a, m.positions[t.z] - a));
            planes.emplace_back(n, glm::dot(n, a));
        }
        mDraws.push_back(d);
    }
    const VkBufferUsageFlags geometry = VK_BUFFER_USAGE_STORAGE_BUFFER_BIT;
    mVertices = vk::makeBuffer<shader::GpuVertex>(ctx, vertices, geometry | VK_BUFFER_USAGE_VERTEX_BUFFER_BIT);
    mIndices = vk::makeBuffer<std::uint32_t>(ctx, indices, geometry | VK_BUFFER_USAGE_INDEX_BUFFER_BIT);
    mPlanes = vk::makeBuffer<glm::vec4>(ctx, planes, geometry);

    std::vector<shader::GpuMaterial> materials;
    for (const Material& m : scene.materials) {
        materials.push_back(toGpuMaterial(m));
    }
    mMaterials = vk::makeBuffer<shader::GpuMaterial>(ctx, materials, VK_BUFFER_USAGE_STORAGE_BUFFER_BIT);
    for (const Light& l : scene.lights) {
        mGpuLights.push_back(toGpuLight(l));
    }
    mLights = vk::makeBuffer<shader::GpuLight>(ctx, mGpuLights, VK_BUFFER_USAGE_STORAGE_BUFFER_BIT);

    auto uploadRgba8 = [&](const Rgba8Image& img) {
        vk::GpuImage image(ctx, {static_cast<std::uint32_t>(img.width), static_cast<std::uint32_t>(img.height), 1,
                                 VK_FORMAT_R8G8B8A8_SRGB, VK_IMAGE_USAGE_SAMPLED_BIT});
        image.upload(ctx, img.texels.data(), img.texels.size());
        return image;
    };
    for (const Texture& t : scene.textures) {
        mTextures.push_back(uploadRgba8(t.image));
    }
    mTextures.push_back(uploadRgba8({1, 1, {255, 255, 255, 255}}));
    mTextureSampler = vk::makeSampler(ctx.device(), VK_FILTER_LINEAR, VK_SAMPLER_ADDRESS_MODE_REPEAT,
                                      VK_SAMPLER_ADDRESS_MODE_REPEAT);

    // Environment: the map premultiplied by its scale, or a 1x1 constant (black when absent).
    const Environment& env = scene.environment;
    std::vector<glm::vec4> texels;
    std::uint32_t w = 1, h = 1;
    if (env.hasMap()) {
        w = static_cast<std::uint32_t>(env.map.width());
        h = static_cast<std::uint32_t>(env.map.height());
        for (const glm::vec3& p : env.map.pixels()) {
            texels.emplace_back(p * env.scale, 1.0f);
        }
    } else {
        texels.emplace_back(env.present ? env.radiance * env.scale : glm::vec3(0.0f), 1.0f);
    }
    mEnvironment = vk::GpuImage(ctx, {w, h, 1, VK_FORMAT_R32G32B32A32_SFLOAT, VK_IMAGE_USAGE_SAMPLED_BIT});
    mEnvironment.upload(ctx, texels.data(), texels.size() * sizeof(glm::vec4));
    // Longitude wraps around; latitude stops at the poles.
    mEnvironmentSampler = vk::makeSampler(ctx.device(), VK_FILTER_LINEAR, VK_SAMPLER_ADDRESS_MODE_REPEAT,
                                          VK_SAMPLER_ADDRESS_MODE_CLAMP_TO_EDGE);
}

VkImageView GpuScene::materialTexture(std::uint32_t material) const {
    int t = mScene->materials.at(material).albedoTexture;
    return mTextures[t >= 0 ? static_cast<std::size_t>(t) : mTextures.size() - 1].view();
}

float GpuScene::environmentRotation() const { return glm::radians(mScene->environment.rotationDegrees); }

glm::mat4 GpuScene::modelMatrix(std::uint32_t mesh, double time) const {
    return mScene->meshes[mesh].animation.at(time);
}

void GpuScene::bindGeometry(VkCommandBuffer cmd) const {
    VkBuffer vb = mVertices.get();
    VkDeviceSize offset = 0;
    vkCmdBindVertexBuffers(cmd, 0, 1, &vb, &offset);
    vkCmdBindIndexBuffer(cmd, mIndices.get(), 0, VK_INDEX_TYPE_UINT32);
}

std::vector<VkVertexInputBindingDescription> GpuScene::vertexBindings() {
    return {{0, sizeof(shader::GpuVertex), VK_VERTEX_INPUT_RATE_VERTEX}};
}

std::vector<VkVertexInputAttributeDescription> GpuScene::vertexAttributes() {
    return {{0, 0, VK_FORMAT_R32G32B32A32_SFLOAT, offsetof(shader::GpuVertex, positionU)},
            {1, 0, VK_FORMAT_R32G32B32A32_SFLOAT, offsetof(shader::GpuVertex, normalV)}};
}

} // namespace bl::gpu
