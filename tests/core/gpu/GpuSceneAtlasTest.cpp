// GpuScene with an atlas (issue 10, atlas link): the upload holds exactly the link's atlas
// vertices, atlas stream, indices and triangle maps, the draws keep the scene's triangle numbering,
// and every upload passes the validation layers. Scenes: the Cornell box and McGuire's textured
// teapot.
#include "GpuSceneReadback.h"
#include "atlas/AtlasLink.h"
#include "base/Error.h"
#include "gpu/GpuScene.h"
#include "scene/SceneLoader.h"
#include "support/TestFiles.h"
#include "support/VulkanTest.h"

#include <cstring>

using namespace bl;

namespace {

class GpuSceneAtlas : public bl::test::VulkanTest {
protected:
    void expectUploaded(const Scene& scene, const atlas::AtlasLink& link) {
        gpu::GpuScene plain(ctx(), scene);
        gpu::GpuScene linked(ctx(), scene, &link);
        ASSERT_TRUE(linked.hasAtlas());
        EXPECT_FALSE(plain.hasAtlas());
        const std::vector<shader::GpuVertex> vertices =
            bl::test::readBack<shader::GpuVertex>(ctx(), linked.vertexBuffer(), link.vertices.size());
        EXPECT_EQ(std::memcmp(vertices.data(), link.vertices.data(), vertices.size() * sizeof(shader::GpuVertex)), 0);
        const std::vector<shader::GpuAtlasVertex> stream =
            bl::test::readBack<shader::GpuAtlasVertex>(ctx(), linked.atlasVertexBuffer(), link.atlasVertices.size());
        EXPECT_EQ(std::memcmp(stream.data(), link.atlasVertices.data(), stream.size() * sizeof(shader::GpuAtlasVertex)), 0);
        EXPECT_EQ(bl::test::readBack<std::uint32_t>(ctx(), linked.indexBuffer(), link.indices.size()), link.indices);
        EXPECT_EQ(bl::test::readBack<std::uint32_t>(ctx(), linked.atlasTriangleBuffer(), link.atlasTriangle.size()),
                  link.atlasTriangle);
        EXPECT_EQ(bl::test::readBack<std::uint32_t>(ctx(), linked.sceneTriangleBuffer(), link.sceneTriangle.size()),
                  link.sceneTriangle);
        // Same triangles in the same order: the draws differ only in where their vertices start,
        // and the planes are the same.
        ASSERT_EQ(linked.draws().size(), plain.draws().size());
        for (std::size_t d = 0; d < plain.draws().size(); ++d) {
            EXPECT_EQ(linked.draws()[d].mesh, plain.draws()[d].mesh);
            EXPECT_EQ(linked.draws()[d].firstIndex, plain.draws()[d].firstIndex);
            EXPECT_EQ(linked.draws()[d].indexCount, plain.draws()[d].indexCount);
            EXPECT_EQ(linked.draws()[d].vertexOffset, link.firstVertex[d]);
        }
        EXPECT_EQ(bl::test::readBack<glm::vec4>(ctx(), linked.planeBuffer(), scene.triangleCount()),
                  bl::test::readBack<glm::vec4>(ctx(), plain.planeBuffer(), scene.triangleCount()));
        // Without an atlas, asking for its buffers is an error, not a null handle.
        EXPECT_THROW(plain.atlasVertexBuffer(), Error);
        EXPECT_THROW(plain.sceneTriangleBuffer(), Error);
    }
};

} // namespace

TEST_F(GpuSceneAtlas, CornellBoxUpload) {
    Scene scene = loadScene(bl::test::sourcePath("data/cornell-box/cornell.toml"));
    const atlas::Atlas atlas = atlas::buildAtlas(scene, atlas::AtlasOptions{256});
    expectUploaded(scene, atlas::linkAtlas(scene, atlas));
}

TEST_F(GpuSceneAtlas, TexturedTeapotUpload) {
    BL_SKIP_WITHOUT_SHARED("data/glossy/teapot/teapot.obj");
    Scene scene = loadScene(bl::test::sharedPath("data/glossy/teapot/teapot.obj"));
    const atlas::Atlas atlas = atlas::buildAtlas(scene, atlas::AtlasOptions{512});
    expectUploaded(scene, atlas::linkAtlas(scene, atlas));
}

TEST_F(GpuSceneAtlas, LinkOfAnotherSceneIsAnError) {
    Scene scene = loadScene(bl::test::sourcePath("data/cornell-box/cornell.toml"));
    const atlas::AtlasLink link = atlas::linkAtlas(scene, atlas::buildAtlas(scene, atlas::AtlasOptions{128}));
    scene.meshes.pop_back();
    const std::string message = bl::test::errorOf([&] { gpu::GpuScene(ctx(), scene, &link); });
    EXPECT_NE(message.find("does not fit the scene"), std::string::npos) << message;
}

TEST(GpuSceneAtlasLayout, SecondStreamBesideTheFirst) {
    // The plain layout is unchanged; the atlas layout adds binding 1 at locations 2 and 3.
    ASSERT_EQ(gpu::GpuScene::vertexBindings().size(), 1u);
    ASSERT_EQ(gpu::GpuScene::vertexAttributes().size(), 2u);
    const auto bindings = gpu::GpuScene::atlasVertexBindings();
    const auto attributes = gpu::GpuScene::atlasVertexAttributes();
    ASSERT_EQ(bindings.size(), 2u);
    EXPECT_EQ(bindings[1].binding, shader::kAtlasVertexBinding);
    EXPECT_EQ(bindings[1].stride, sizeof(shader::GpuAtlasVertex));
    ASSERT_EQ(attributes.size(), 4u);
    EXPECT_EQ(attributes[2].location, shader::kAtlasVertexLocationUv);
    EXPECT_EQ(attributes[2].format, VK_FORMAT_R32G32_SFLOAT);
    EXPECT_EQ(attributes[3].location, shader::kAtlasVertexLocationPage);
    EXPECT_EQ(attributes[3].format, VK_FORMAT_R32_UINT);
    EXPECT_EQ(attributes[3].offset, offsetof(shader::GpuAtlasVertex, page));
}
