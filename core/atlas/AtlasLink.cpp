#include "atlas/AtlasLink.h"

#include "base/Error.h"

#include <limits>

namespace bl::atlas {

namespace {

constexpr std::uint32_t kUnmapped = std::numeric_limits<std::uint32_t>::max();

void checkSizes(const Scene& scene, const Atlas& atlas) {
    const std::size_t meshes = scene.meshes.size();
    if (atlas.meshes.size() != meshes || atlas.vertexPages.size() != meshes || atlas.vertexSources.size() != meshes ||
        atlas.triangleSources.size() != meshes) {
        throw Error("atlas link: the atlas has " + std::to_string(atlas.meshes.size()) + " meshes, the scene " +
                    std::to_string(meshes) + ": it was built from another scene");
    }
    for (std::size_t m = 0; m < meshes; ++m) {
        const Mesh& am = atlas.meshes[m];
        if (am.triangles.size() != scene.meshes[m].triangles.size() ||
            atlas.triangleSources[m].size() != am.triangles.size() || atlas.vertexPages[m].size() != am.positions.size() ||
            atlas.vertexSources[m].size() != am.positions.size() || am.uvs.size() != am.positions.size()) {
            throw Error("atlas link: mesh " + std::to_string(m) + " (" + scene.meshes[m].name + ") has " +
                        std::to_string(scene.meshes[m].triangles.size()) + " triangles in the scene and " +
                        std::to_string(am.triangles.size()) + " in the atlas, or its per-vertex lists disagree");
        }
    }
}

} // namespace

AtlasLink linkAtlas(const Scene& scene, const Atlas& atlas) {
    checkSizes(scene, atlas);
    AtlasLink link;
    link.firstTriangle = firstSceneTriangles(scene);
    const std::uint32_t triangles = link.firstTriangle.back();
    link.atlasTriangle.assign(triangles, kUnmapped);
    link.sceneTriangle.assign(triangles, kUnmapped);
    for (std::size_t m = 0; m < scene.meshes.size(); ++m) {
        const Mesh& sceneMesh = scene.meshes[m];
        const Mesh& atlasMesh = atlas.meshes[m];
        const std::uint32_t first = link.firstTriangle[m];
        for (std::uint32_t a = 0; a < atlasMesh.triangles.size(); ++a) {
            const std::uint32_t s = atlas.triangleSources[m][a];
            if (s >= sceneMesh.triangles.size() || link.atlasTriangle[first + s] != kUnmapped) {
                throw Error("atlas link: mesh " + std::to_string(m) + " (" + sceneMesh.name + "): atlas triangle " +
                            std::to_string(a) + " comes from scene triangle " + std::to_string(s) +
                            ", out of range or already taken");
            }
            link.atlasTriangle[first + s] = first + a;
            link.sceneTriangle[first + a] = first + s;
        }

        if (link.vertices.size() > std::size_t(std::numeric_limits<std::int32_t>::max())) {
            throw Error("atlas link: over 2^31 atlas vertices, more than a draw's vertex offset holds");
        }
        link.firstVertex.push_back(std::int32_t(link.vertices.size()));
        for (std::size_t v = 0; v < atlasMesh.positions.size(); ++v) {
            const std::uint32_t source = atlas.vertexSources[m][v];
            const glm::vec2 materialUv = sceneMesh.uvs.empty() ? glm::vec2(0.0f) : sceneMesh.uvs.at(source);
            link.vertices.push_back({glm::vec4(atlasMesh.positions[v], materialUv.x),
                                     glm::vec4(atlasMesh.normals[v], materialUv.y)});
            link.atlasVertices.push_back({atlasMesh.uvs[v], atlas.vertexPages[m][v], 0u});
        }
        // Every scene triangle was mapped above: the counts are equal and no source repeats.
        for (std::uint32_t s = 0; s < sceneMesh.triangles.size(); ++s) {
            const glm::uvec3& corners = atlasMesh.triangles[link.atlasTriangle[first + s] - first];
            link.indices.insert(link.indices.end(), {corners.x, corners.y, corners.z});
        }
    }
    return link;
}

} // namespace bl::atlas
