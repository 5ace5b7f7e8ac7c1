// Buffer references to a bundle's storage (device addresses: one binding is not limited to
// lavapipe's 128 MiB, and the pool can be reallocated without new descriptors).
#ifndef BL_BUNDLE_BUFFERS_GLSL
#define BL_BUNDLE_BUFFERS_GLSL
#extension GL_EXT_buffer_reference : require
#extension GL_EXT_buffer_reference_uvec2 : require
#include "shared/BundleTypes.h"

layout(buffer_reference, std430, buffer_reference_align = 4) buffer BundleHeads { uint heads[]; };
layout(buffer_reference, std430, buffer_reference_align = 8) buffer BundleNodes { BundleNode nodes[]; };
layout(buffer_reference, std430, buffer_reference_align = 4) buffer BundleShadingPayload { BundleShading shading[]; };
layout(buffer_reference, std430, buffer_reference_align = 8) buffer BundleSurfacePayload { BundleSurface surfaces[]; };
layout(buffer_reference, std430, buffer_reference_align = 16) buffer BundleCounterBlock { BundleCounters counters; };

#endif
