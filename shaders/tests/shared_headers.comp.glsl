#version 460
#extension GL_GOOGLE_include_directive : require
// Compiles every shared header as GLSL, so a C++-only construct in one breaks the build at once.
#include "shared/Bindings.h"
#include "shared/Brdf.h"
#include "shared/BrdfSampling.h"
#include "shared/Camera.h"
#include "shared/CubeFaces.h"
#include "shared/EnvMap.h"
#include "shared/Lights.h"
#include "shared/Random.h"
#include "shared/Sampling.h"

layout(local_size_x = 1) in;
layout(set = 0, binding = 0) buffer Out { vec4 values[]; };

void main() {
    RandomStream rs = blRandomStream(1u, 2u, 3u);
    GpuMaterial m;
    m.albedo = vec3(0.5);
    m.specular = vec3(0.3);
    m.exponentU = 10.0;
    m.exponentV = 20.0;
    vec3 n = vec3(0, 0, 1);
    vec3 wi = normalize(vec3(1, 0, 1));
    vec3 wo = blSampleBrdf(m, m.albedo, n, wi, vec3(blRandom(rs), blRandom(rs), blRandom(rs)));
    values[0] = vec4(blEvalBrdf(m, m.albedo, n, wi, wo), blBrdfPdf(m, m.albedo, n, wi, wo));
}
