// Host/device struct layouts: the offsets std430 gives these members in GLSL.
#include <cstddef>
#include <gtest/gtest.h>
#include <modes/raster/RasterShared.h>
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
