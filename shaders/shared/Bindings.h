// Descriptor set and binding numbers, defined once for the host and the shaders.
#ifndef BL_SHARED_BINDINGS_H
#define BL_SHARED_BINDINGS_H
#include "Prelude.h"

BL_NAMESPACE_BEGIN

// G-buffer pass, set 0 (per frame).
BL_CONST uint kGBufferBindingCamera = 0u;    // uniform GpuCamera
BL_CONST uint kGBufferBindingMaterials = 1u; // storage GpuMaterial[]
BL_CONST uint kGBufferBindingVertices = 2u;  // storage GpuVertex[] (the surface channel's triangles)
BL_CONST uint kGBufferBindingIndices = 3u;   // storage uint[]
// G-buffer pass, set 1 (per material): its albedo texture (a white texel when untextured).
BL_CONST uint kGBufferBindingAlbedoTexture = 0u;

// G-buffer colour attachments.
BL_CONST uint kGBufferPosition = 0u; // xyz world position, w = 1 where a surface was hit
BL_CONST uint kGBufferNormal = 1u;   // xyz shading normal facing the camera, w = material index
BL_CONST uint kGBufferAlbedo = 2u;   // rgb albedo (texture applied)
BL_CONST uint kGBufferEmission = 3u; // rgb emitted radiance toward the camera (front faces only)
BL_CONST uint kGBufferSurface = 4u;  // the sample's triangle and where in it (atlas gather, reprojection,
                                     // first path vertices): x, y = global triangle index (GpuScene order)
                                     // low and high 16 bits (exact in float), z, w = barycentrics (b1, b2);
                                     // decode with blGBufferSurface (shaders/gpu/CameraSet.glsl)
BL_CONST uint kGBufferAttachmentCount = 5u;
// G-buffer specialization constants (gbuffer.frag.glsl), constant_id = index: the texture lookup
// only where some material has an albedo texture, the surface channel (six vertex loads and the
// barycentrics) only where the pass's reader decodes it; lavapipe runs a fragment's every branch
// under a mask, so they cost every fragment unless compiled out
// (experiments/bench/results/specialization-lavapipe-2026-11-28.md).
BL_CONST uint kGBufferSpecTextured = 0u;
BL_CONST uint kGBufferSpecSurface = 1u;
BL_CONST uint kGBufferSpecCount = 2u;

// Camera set: set 0 of every shading pass that runs per camera pixel (core/gpu/CameraPass.h,
// shaders/gpu/CameraSet.glsl); each mode adds its own set 1.
BL_CONST uint kCameraSet = 0u;
BL_CONST uint kCameraBindingGBuffer = 0u;     // storage image[4] (rgba32f), the G-buffer
BL_CONST uint kCameraBindingCamera = 1u;      // uniform GpuCamera of the last G-buffer record
BL_CONST uint kCameraBindingMaterials = 2u;   // storage GpuMaterial[]
BL_CONST uint kCameraBindingEnvironment = 3u; // combined sampler, lat-long rgba32f
BL_CONST uint kCameraBindingAccum = 4u;       // storage image array (rgba32f), Accumulation.h's slots

// Raster shading pass, set 1.
BL_CONST uint kRasterSet = 1u;
BL_CONST uint kRasterBindingLights = 0u;     // storage GpuLight[]
BL_CONST uint kRasterBindingShadowMaps = 1u; // storage image 2D array (rgba16ui, gpu/ShadowTexel.glsl), layers 6 l .. 6 l + 5 = light l
BL_CONST uint kRasterBindingEmitterPoints = 2u;     // storage GpuEmitterPoint[] (EmitterPointPass)
BL_CONST uint kRasterBindingEmitterShadowMaps = 3u; // storage image 2D array (rgba16ui, gpu/ShadowTexel.glsl), 6 layers per emitter point
BL_CONST uint kRasterBindingEnvironmentShadows = 4u;    // storage GpuEnvironmentShadow[] (EnvironmentShadowPass)
BL_CONST uint kRasterBindingEnvironmentShadowMaps = 5u; // storage image 2D array (rgba32f: depth, normal), a depth map per direction

// Skylight visibility pass, set 1.
BL_CONST uint kSkylightSet = 1u;
BL_CONST uint kSkylightBindingFrame = 0u;    // uniform BundleFrame of this direction (and tile)
BL_CONST uint kSkylightBindingDepthMap = 1u; // storage image (rgba32f: depth, normal): visibility = depth_map

BL_NAMESPACE_END
#endif
