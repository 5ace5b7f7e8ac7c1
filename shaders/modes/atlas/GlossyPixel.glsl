// The camera sample of a pixel as the glossy passes of mode atlas see it (gather.comp.glsl,
// highlight.comp.glsl). Include after gpu/CameraSet.glsl.
#ifndef BL_ATLAS_GLOSSY_PIXEL_GLSL
#define BL_ATLAS_GLOSSY_PIXEL_GLSL

// Whether `pixel`'s camera sample hit a surface whose material has a glossy lobe; then its
// material, position, shading normal (facing the camera) and direction toward the eye.
bool blAtlasGlossyPixel(ivec2 pixel, out GpuMaterial m, out vec3 p, out vec3 n, out vec3 eye) {
    if (!blCameraHitSurface(pixel)) {
        return false;
    }
    vec4 normalMaterial = imageLoad(gbuffer[kGBufferNormal], pixel);
    m = materials[uint(normalMaterial.w)];
    p = imageLoad(gbuffer[kGBufferPosition], pixel).xyz;
    n = normalize(normalMaterial.xyz);
    eye = normalize(camera.position - p);
    return m.specular.x + m.specular.y + m.specular.z > 0.0;
}

#endif
