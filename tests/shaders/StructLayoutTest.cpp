// Host/device struct layouts: the offsets std430 gives these members in GLSL.
#include <cstddef>
#include <gtest/gtest.h>
#include <modes/raster/RasterShared.h>
#include <shared/BundleTypes.h>
#include <shared/GpuTypes.h>

using namespace bl::shader;

TEST(StructLayout, MatchesStd430) {
    EXPECT_EQ(offsetof(GpuVertex, normalV), 16u);
    EXPECT_EQ(offsetof(GpuAtlasVertex, page), 8u);
    EXPECT_EQ(sizeof(GpuAtlasVertex), 16u);
    EXPECT_EQ(offsetof(GpuMaterial, albedoTexture), 12u);
    EXPECT_EQ(offsetof(GpuMaterial, specular), 16u);
    EXPECT_EQ(offsetof(GpuMaterial, exponentU), 28u);
    EXPECT_EQ(offsetof(GpuMaterial, exponentV), 32u);
    EXPECT_EQ(offsetof(GpuLight, type), 12u);
    EXPECT_EQ(offsetof(GpuLight, intensity), 16u);
    EXPECT_EQ(offsetof(GpuLight, cosOuter), 28u);
    EXPECT_EQ(offsetof(GpuLight, direction), 32u);
    EXPECT_EQ(offsetof(GpuLight, cosInner), 44u);
    EXPECT_EQ(offsetof(GpuCamera, position), 64u);
    EXPECT_EQ(offsetof(GpuCamera, tanHalfX), 76u);
    EXPECT_EQ(offsetof(GpuCamera, up), 112u);
    EXPECT_EQ(offsetof(GpuCamera, height), 124u);
    EXPECT_EQ(offsetof(GBufferPush, emission), 64u);
    EXPECT_EQ(offsetof(GBufferPush, material), 76u);
    EXPECT_EQ(offsetof(GBufferPush, jitter), 80u);
    EXPECT_EQ(offsetof(ShadowPush, lightPosition), 64u);
    EXPECT_EQ(offsetof(ShadowPush, nearPlane), 76u);
    EXPECT_EQ(offsetof(ShadowPush, face), 80u);
    EXPECT_EQ(offsetof(RasterPush, samplePosition), 16u);
    EXPECT_EQ(offsetof(RasterPush, width), 24u);
    EXPECT_LE(sizeof(GBufferPush), 128u); // the guaranteed push-constant size
    EXPECT_LE(sizeof(ShadowPush), 128u);
}

// The bundle structs shaders read through buffer references and push constants: std430 offsets
// (vec3 aligned to 16, a struct to its largest member), so host and device agree member by member.
TEST(StructLayout, BundleStructsMatchStd430) {
    EXPECT_EQ(offsetof(BundleFrame, pixelSize), 12u);
    EXPECT_EQ(offsetof(BundleFrame, axisX), 16u);
    EXPECT_EQ(offsetof(BundleFrame, width), 28u);
    EXPECT_EQ(offsetof(BundleFrame, axisY), 32u);
    EXPECT_EQ(offsetof(BundleFrame, height), 44u);
    EXPECT_EQ(offsetof(BundleFrame, direction), 48u);
    EXPECT_EQ(offsetof(BundleFrame, depthNear), 60u);
    EXPECT_EQ(offsetof(BundleFrame, depthFar), 64u);
    EXPECT_EQ(offsetof(BundleFrame, depthEpsilon), 68u);
    EXPECT_EQ(offsetof(BundleFrame, tileX), 72u);
    EXPECT_EQ(offsetof(BundleFrame, gridWidth), 80u);
    EXPECT_EQ(sizeof(BundleFrame), 96u); // a multiple of its 16-byte alignment: frames[] has no gaps
    EXPECT_EQ(offsetof(BundleNode, next), 4u);
    EXPECT_EQ(sizeof(BundleNode), 8u);
    EXPECT_EQ(offsetof(BundleHit, material), 4u);
    EXPECT_EQ(offsetof(BundleHit, uv), 8u);
    EXPECT_EQ(offsetof(BundleHit, id), 16u);
    EXPECT_EQ(offsetof(BundleHit, barycentric), 20u);
    EXPECT_EQ(offsetof(BundleHit, plane), 24u);
    EXPECT_EQ(sizeof(BundleHit), 32u);
    EXPECT_EQ(offsetof(BundleSplat, radius), 12u);
    EXPECT_EQ(offsetof(BundleSplat, normal), 16u);
    EXPECT_EQ(offsetof(BundleSplat, material), 28u);
    EXPECT_EQ(sizeof(BundleSplat), 32u);
    EXPECT_EQ(offsetof(BundleCounters, excessHigh), 12u);
    EXPECT_EQ(offsetof(BundleDrawPush, frameAddress), 64u);
    EXPECT_EQ(offsetof(BundleDrawPush, splatAddress), 104u);
    EXPECT_EQ(offsetof(BundleDrawPush, unused0), 112u);
    EXPECT_EQ(offsetof(BundleDrawPush, vertexOffset), 124u);
    EXPECT_EQ(sizeof(BundleDrawPush), 128u); // the push-constant size every device guarantees
    EXPECT_EQ(offsetof(BundlePoolView, previous), 40u);
    EXPECT_EQ(offsetof(BundlePoolView, slotPixels), 48u);
    EXPECT_EQ(offsetof(BundlePoolView, sorted), 60u);
    EXPECT_EQ(offsetof(BundlePoolPush, slot), 64u);
    EXPECT_EQ(offsetof(BundlePoolPush, statsAddress), 72u);
    EXPECT_EQ(offsetof(BundleListStats, reachableNodes), 8u);
    EXPECT_EQ(sizeof(BundleDepthMapPush), 64u);
}
