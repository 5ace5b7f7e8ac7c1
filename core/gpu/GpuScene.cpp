#include "gpu/GpuScene.h"

#include "base/Error.h"
#include "scene/ShaderConversions.h"

#include <algorithm>
#include <cmath>

namespace bl::gpu {

namespace {

void checkLink(const Scene& scene, const atlas::AtlasLink& link) {
    const std::size_t meshes = scene.meshes.size();
    const bool fits = link.firstTriangle.size() == meshes + 1 && link.firstVertex.size() == meshes &&
                      link.atlasVertices.size() == link.vertices.size() &&
                      link.indices.size() == 3 * std::size_t(link.firstTriangle.back()) &&
                      link.atlasTriangle.size() == link.firstTriangle.back() &&
                      link.sceneTriangle.size() == link.firstTriangle.back() &&
                      link.firstTriangle.back() == scene.triangleCount();
    if (!fits) {
        throw Error("GpuScene: the atlas link does not fit the scene (" + std::to_string(scene.triangleCount()) +
                    " triangles in " + std::to_string(meshes) + " meshes; the link has " +
                    std::to_string(link.atlasTriangle.size()) + " triangles in " +
                    std::to_string(link.firstVertex.size()) + " meshes): link the atlas built from this scene");
    }
}

} // namespace

glm::vec4 trianglePlane(const glm::vec3& a, const glm::vec3& b, const glm::vec3& c) {
    // Differences and products of floats are exact or nearly so in double: no cancellation in the
    // cross product of a sliver, no overflow or underflow anywhere in float's range.
    const glm::dvec3 pa(a);
    const glm::dvec3 n = glm::cross(glm::dvec3(b) - pa, glm::dvec3(c) - pa);
    const double length = glm::length(n);
    if (!(length > 0.0) || !std::isfinite(length)) {
        return kNoPlane;
    }
    const glm::dvec3 unit = n / length;
    const glm::vec4 plane(glm::vec3(unit), float(glm::dot(unit, pa)));
    const bool finite = std::isfinite(plane.x) && std::isfinite(plane.y) && std::isfinite(plane.z) && std::isfinite(plane.w);
    return finite ? plane : kNoPlane;
}

GpuScene::GpuScene(const vk::Context& ctx, const Scene& scene, const atlas::AtlasLink* atlas)
    : mScene(&scene), mFeatures(scene.features()) {
    mRadius = std::max(mFeatures.bounds.radius(), 1e-30f);
    if (atlas) checkLink(scene, *atlas);
    // With an atlas, its vertices and its indices (the same triangles in the same order).
    std::vector<shader::GpuVertex> vertices;
    std::vector<std::uint32_t> indices;
    std::vector<glm::vec4> planes;
    for (std::uint32_t i = 0; i < scene.meshes.size(); ++i) {
        const Mesh& m = scene.meshes[i];
        const std::int32_t vertexOffset = atlas ? atlas->firstVertex[i] : static_cast<std::int32_t>(vertices.size());
        mDraws.push_back({i, 3 * mTriangleCount, static_cast<std::uint32_t>(m.triangles.size() * 3), vertexOffset});
        mTriangleCount += static_cast<std::uint32_t>(m.triangles.size());
        for (std::size_t v = 0; !atlas && v < m.positions.size(); ++v) {
            glm::vec2 uv = m.uvs.empty() ? glm::vec2(0.0f) : m.uvs[v];
            vertices.push_back({glm::vec4(m.positions[v], uv.x), glm::vec4(m.normals[v], uv.y)});
        }
        for (const glm::uvec3& t : m.triangles) {
            if (!atlas) indices.insert(indices.end(), {t.x, t.y, t.z});
            planes.push_back(trianglePlane(m.positions[t.x], m.positions[t.y], m.positions[t.z]));
        }
    }
    // Transfer source too: tests and tools read the geometry back.
    const VkBufferUsageFlags geometry = VK_BUFFER_USAGE_STORAGE_BUFFER_BIT | VK_BUFFER_USAGE_TRANSFER_SRC_BIT;
    const VkBufferUsageFlags vertexUse = geometry | VK_BUFFER_USAGE_VERTEX_BUFFER_BIT;
    mVertices = vk::makeBuffer<shader::GpuVertex>(ctx, atlas ? atlas->vertices : vertices, vertexUse);
    mIndices = vk::makeBuffer<std::uint32_t>(ctx, atlas ? atlas->indices : indices,
                                             geometry | VK_BUFFER_USAGE_INDEX_BUFFER_BIT);
    mPlanes = vk::makeBuffer<glm::vec4>(ctx, planes, geometry);
    if (atlas) {
        mHasAtlas = true;
        mAtlasVertices = vk::makeBuffer<shader::GpuAtlasVertex>(ctx, atlas->atlasVertices, vertexUse);
        mAtlasTriangles = vk::makeBuffer<std::uint32_t>(ctx, atlas->atlasTriangle, geometry);
        mSceneTriangles = vk::makeBuffer<std::uint32_t>(ctx, atlas->sceneTriangle, geometry);
    }

    std::vector<shader::GpuMaterial> materials;
    for (const Material& m : scene.materials) {
        materials.push_back(toGpuMaterial(m));
    }
    mMaterials = vk::makeBuffer<shader::GpuMaterial>(ctx, materials, VK_BUFFER_USAGE_STORAGE_BUFFER_BIT);
    for (const Light& l : scene.lightsAt(0.0)) {
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

void GpuScene::setLightTime(const vk::Context& ctx, double time) {
    mGpuLights.clear();
    for (const Light& l : mScene->lightsAt(time)) {
        mGpuLights.push_back(toGpuLight(l));
    }
    if (!mGpuLights.empty()) {
        mLights.upload(ctx, mGpuLights.data(), mGpuLights.size() * sizeof(shader::GpuLight));
    }
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

void GpuScene::bindAtlasStream(VkCommandBuffer cmd) const {
    VkBuffer vb = atlasVertexBuffer();
    VkDeviceSize offset = 0;
    vkCmdBindVertexBuffers(cmd, shader::kAtlasVertexBinding, 1, &vb, &offset);
}

namespace {
VkBuffer requireAtlas(bool present, const vk::Buffer& buffer, const char* what) {
    if (!present) {
        throw Error(std::string("GpuScene: ") + what + " asked of a scene uploaded without an atlas");
    }
    return buffer.get();
}
} // namespace

VkBuffer GpuScene::atlasVertexBuffer() const { return requireAtlas(mHasAtlas, mAtlasVertices, "the atlas stream"); }
VkBuffer GpuScene::atlasTriangleBuffer() const {
    return requireAtlas(mHasAtlas, mAtlasTriangles, "the atlas triangle map");
}
VkBuffer GpuScene::sceneTriangleBuffer() const {
    return requireAtlas(mHasAtlas, mSceneTriangles, "the scene triangle map");
}

std::vector<VkVertexInputBindingDescription> GpuScene::vertexBindings() {
    return {{0, sizeof(shader::GpuVertex), VK_VERTEX_INPUT_RATE_VERTEX}};
}

std::vector<VkVertexInputAttributeDescription> GpuScene::vertexAttributes() {
    return {{0, 0, VK_FORMAT_R32G32B32A32_SFLOAT, offsetof(shader::GpuVertex, positionU)},
            {1, 0, VK_FORMAT_R32G32B32A32_SFLOAT, offsetof(shader::GpuVertex, normalV)}};
}

std::vector<VkVertexInputBindingDescription> GpuScene::atlasVertexBindings() {
    std::vector<VkVertexInputBindingDescription> bindings = vertexBindings();
    bindings.push_back({shader::kAtlasVertexBinding, sizeof(shader::GpuAtlasVertex), VK_VERTEX_INPUT_RATE_VERTEX});
    return bindings;
}

std::vector<VkVertexInputAttributeDescription> GpuScene::atlasVertexAttributes() {
    std::vector<VkVertexInputAttributeDescription> attributes = vertexAttributes();
    attributes.push_back({shader::kAtlasVertexLocationUv, shader::kAtlasVertexBinding, VK_FORMAT_R32G32_SFLOAT,
                          offsetof(shader::GpuAtlasVertex, uv)});
    attributes.push_back({shader::kAtlasVertexLocationPage, shader::kAtlasVertexBinding, VK_FORMAT_R32_UINT,
                          offsetof(shader::GpuAtlasVertex, page)});
    return attributes;
}

} // namespace bl::gpu
