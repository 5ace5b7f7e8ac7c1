// Specialization constants for what the scene's materials have (glossy lobes, anisotropic ones,
// albedo textures), for passes that evaluate BRDFs or textures per pixel or path vertex: where no
// material has one, its code compiles out of shared/Brdf.h and gpu/PackedTextureLookup.glsl. The
// results are the same; lavapipe, which runs both sides of every branch under a lane mask, stops
// paying for lobes and lookups the scene has none of. Define BL_MATERIAL_SPEC_FIRST (the first
// constant_id of the three, kMaterialSpec* order in shared/MaterialSpecialization.h) and include
// this before anything that includes shared/Brdf.h or gpu/PackedTextureLookup.glsl; the host
// appends gpu::appendMaterialSpecialization.
#ifndef BL_GPU_MATERIAL_SPECIALIZATION_GLSL
#define BL_GPU_MATERIAL_SPECIALIZATION_GLSL
#if defined(BL_SHARED_BRDF_H) || defined(BL_GPU_PACKED_TEXTURE_LOOKUP_GLSL)
#error "include gpu/MaterialSpecialization.glsl before shared/Brdf.h and gpu/PackedTextureLookup.glsl"
#endif
#include "shared/MaterialSpecialization.h"

layout(constant_id = BL_MATERIAL_SPEC_FIRST + kMaterialSpecGlossy) const bool kMaterialGlossy = true;
layout(constant_id = BL_MATERIAL_SPEC_FIRST + kMaterialSpecAnisotropic) const bool kMaterialAnisotropic = true;
layout(constant_id = BL_MATERIAL_SPEC_FIRST + kMaterialSpecTextured) const bool kMaterialTextured = true;
#define BL_GLOSSY_LOBES kMaterialGlossy
#define BL_ANISOTROPIC_LOBES kMaterialAnisotropic
#define BL_ALBEDO_TEXTURES kMaterialTextured
#endif
