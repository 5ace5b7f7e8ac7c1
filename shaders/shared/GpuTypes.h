// Structs shared by the host and the shaders (std430 storage buffers and push constants).
// Sizes and offsets are pinned by static_asserts here and by tests/shaders/StructLayoutTest.cpp.
#ifndef BL_SHARED_GPU_TYPES_H
#define BL_SHARED_GPU_TYPES_H
#include "Prelude.h"

BL_NAMESPACE_BEGIN

// One vertex as the raster passes read it: position + u, normal + v.
struct GpuVertex {
    vec4 positionU;
    vec4 normalV;
};
BL_STATIC_ASSERT(sizeof(GpuVertex) == 32, "GpuVertex layout");

// The optional second vertex stream (GpuScene built with an atlas): where the vertex lies in the
// texture atlas. Atlas charts split vertices at their seams, so such a GpuScene draws the atlas's
// vertices (GpuVertex at binding 0, this at binding 1) with the same triangle order.
struct GpuAtlasVertex {
    vec2 uv;   // atlas uv in [0, 1]^2 of its page, (0, 0) = texel (0, 0) of the page
    uint page; // atlas page
    uint pad0;
};
BL_STATIC_ASSERT(sizeof(GpuAtlasVertex) == 16, "GpuAtlasVertex layout");
BL_CONST uint kAtlasVertexBinding = 1u;       // vertex input binding of GpuAtlasVertex
BL_CONST uint kAtlasVertexLocationUv = 2u;    // vertex shader input: vec2 atlas uv
BL_CONST uint kAtlasVertexLocationPage = 3u;  // vertex shader input: uint page

BL_CONST uint kNoTexture = 0xffffffffu;

// BRDF parameters; the BRDF itself is in Brdf.h. exponentU == exponentV means the isotropic
// normalized Phong lobe, otherwise the Ashikhmin-Shirley lobe.
struct GpuMaterial {
    vec3 albedo;        // Lambertian reflectance: f = albedo / pi
    uint albedoTexture; // index into the texture table, kNoTexture if none
    vec3 specular;      // reflectance of the glossy lobe
    float exponentU;    // Phong exponent (or Ashikhmin-Shirley n_u)
    float exponentV;    // Ashikhmin-Shirley n_v
    uint flags;         // reserved
    uint pad0;
    uint pad1;
};
BL_STATIC_ASSERT(sizeof(GpuMaterial) == 48, "GpuMaterial layout");

BL_CONST uint kLightPoint = 0u;
BL_CONST uint kLightSpot = 1u;

// Point and spot lights (radiant intensity in W/sr). Spot: full intensity inside cosInner,
// smoothstep down to zero at cosOuter (see Lights.h).
struct GpuLight {
    vec3 position;
    uint type;
    vec3 intensity;
    float cosOuter;
    vec3 direction; // spot axis, unit length
    float cosInner;
};
BL_STATIC_ASSERT(sizeof(GpuLight) == 48, "GpuLight layout");

// Pinhole camera as both the rasterizer and ray generation use it (Camera.h).
struct GpuCamera {
    mat4 viewProj;
    vec3 position;
    float tanHalfX; // tan(horizontal fov / 2)
    vec3 forward;
    float tanHalfY; // tan(vertical fov / 2)
    vec3 right;
    float width;
    vec3 up; // true up = cross(right, forward)
    float height;
};
BL_STATIC_ASSERT(sizeof(GpuCamera) == 128, "GpuCamera layout");

// Per-draw push constants of the G-buffer pass.
struct GBufferPush {
    mat4 model;      // rigid transform at the frame's time
    vec3 emission;   // emitted radiance of the mesh's front face
    uint material;   // index into the material buffer
    vec2 jitter;     // sub-pixel offset in NDC units
    uint firstTriangle; // global index of the draw's first triangle (GpuScene order)
    uint vertexOffset;  // the draw's vertex offset
};
BL_STATIC_ASSERT(sizeof(GBufferPush) == 96, "GBufferPush layout");

// Per-draw push constants of the shadow cube pass.
struct ShadowPush {
    mat4 model;
    vec3 lightPosition;
    float nearPlane; // world units; geometry closer than this to the light is clipped
    uint face;       // cube face 0..5, see CubeFaces.h
    uint pad0;
    uint pad1;
    uint pad2;
};
BL_STATIC_ASSERT(sizeof(ShadowPush) == 96, "ShadowPush layout");
// Specialization constant of the shadow cube shaders: 1 to store each texel's surface normal (the
// crease rule of multi-tap lookups needs it), 0 to leave it out (cubes only one-tap lookups read).
BL_CONST uint kShadowSpecNormals = 0u;

BL_NAMESPACE_END
#endif
