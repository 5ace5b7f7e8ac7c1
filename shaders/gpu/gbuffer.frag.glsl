#version 460
#extension GL_GOOGLE_include_directive : require
// G-buffer: world position, shading normal turned toward the camera (two-sided reflection),
// albedo with its texture, emitted radiance of front faces only (one-sided emission), and the
// sample's triangle with its barycentrics.
#include "shared/Barycentrics.h"
#include "shared/Bindings.h"
#include "shared/GpuTypes.h"

layout(location = 0) in vec3 inWorld;
layout(location = 1) in vec3 inNormal;
layout(location = 2) in vec2 inUv;

layout(set = 0, binding = kGBufferBindingCamera) uniform CameraBlock { GpuCamera camera; };
layout(set = 0, binding = kGBufferBindingMaterials) readonly buffer MaterialBlock { GpuMaterial materials[]; };
layout(set = 0, binding = kGBufferBindingVertices) readonly buffer VertexBlock { GpuVertex vertices[]; };
layout(set = 0, binding = kGBufferBindingIndices) readonly buffer IndexBlock { uint indices[]; };
layout(set = 1, binding = kGBufferBindingAlbedoTexture) uniform sampler2D albedoTexture;
layout(push_constant) uniform PushBlock { GBufferPush push; };
layout(constant_id = kGBufferSpecTextured) const bool kTextured = true;
layout(constant_id = kGBufferSpecSurface) const bool kSurface = true;

layout(location = kGBufferPosition) out vec4 outPosition;
layout(location = kGBufferNormal) out vec4 outNormal;
layout(location = kGBufferAlbedo) out vec4 outAlbedo;
layout(location = kGBufferEmission) out vec4 outEmission;
layout(location = kGBufferSurface) out vec4 outSurface;

// Barycentrics of the sample in its triangle, from the triangle's corners in world space.
vec2 sampleBarycentrics(uint triangle) {
    uint first = 3u * triangle;
    vec3 a = (push.model * vec4(vertices[indices[first] + push.vertexOffset].positionU.xyz, 1.0)).xyz;
    vec3 b = (push.model * vec4(vertices[indices[first + 1u] + push.vertexOffset].positionU.xyz, 1.0)).xyz;
    vec3 c = (push.model * vec4(vertices[indices[first + 2u] + push.vertexOffset].positionU.xyz, 1.0)).xyz;
    return blTriangleBarycentrics(inWorld - a, b - a, c - a);
}

void main() {
    float len = length(inNormal);
    // Interpolating opposite vertex normals can cancel: fall back to the geometric normal.
    vec3 n = len > 1e-20 ? inNormal / len : normalize(cross(dFdx(inWorld), dFdy(inWorld)));
    if (dot(n, camera.position - inWorld) < 0.0) {
        n = -n;
    }
    GpuMaterial m = materials[push.material];
    vec3 albedo = m.albedo;
    if (kTextured && m.albedoTexture != kNoTexture) {
        // OBJ texture coordinates have v = 0 at the bottom; image row 0 is the top.
        albedo = texture(albedoTexture, vec2(inUv.x, 1.0 - inUv.y)).rgb;
    }
    outPosition = vec4(inWorld, 1.0);
    outNormal = vec4(n, float(push.material));
    outAlbedo = vec4(albedo, 1.0);
    outEmission = vec4(gl_FrontFacing ? push.emission : vec3(0.0), 1.0);
    uint triangle = push.firstTriangle + uint(gl_PrimitiveID);
    outSurface = kSurface ? vec4(float(triangle & 0xffffu), float(triangle >> 16), sampleBarycentrics(triangle))
                          : vec4(0.0);
}
