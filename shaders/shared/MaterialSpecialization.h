// The order of the material specialization constants (gpu/MaterialSpecialization.glsl), after a
// pass's own: constant_id = the pass's first + these. Host: gpu::appendMaterialSpecialization.
#ifndef BL_SHARED_MATERIAL_SPECIALIZATION_H
#define BL_SHARED_MATERIAL_SPECIALIZATION_H
#include "Prelude.h"

BL_NAMESPACE_BEGIN

BL_CONST uint kMaterialSpecGlossy = 0u;      // 1: some material has a glossy lobe
BL_CONST uint kMaterialSpecAnisotropic = 1u; // 1: some glossy lobe is anisotropic (Ashikhmin-Shirley)
BL_CONST uint kMaterialSpecTextured = 2u;    // 1: some material has an albedo texture
BL_CONST uint kMaterialSpecCount = 3u;

BL_NAMESPACE_END
#endif
