// Mode bidir's environment light by bundles ([TO12] section 3 and Eq. 2; modes/bidir/
// EnvironmentBundles.h): host/device definitions of the block the evaluation pass reads.
#ifndef BL_BIDIR_ENVIRONMENT_H
#define BL_BIDIR_ENVIRONMENT_H
#include "../../shared/Prelude.h"

BL_NAMESPACE_BEGIN

// The evaluation pass's set 1 (BidirShared.h): the environment bundles of this frame.
BL_CONST uint kBidirBindingEnvironment = 10u;

// The block's header: which pool slots hold environment bundles (none: count = 0).
struct BidirEnvironmentHeader {
    uint firstSlot; // pool slot of environment bundle 0
    uint count;     // E environment bundles this frame
    uint pad0;
    uint pad1;
};
BL_STATIC_ASSERT(sizeof(BidirEnvironmentHeader) == 16, "BidirEnvironmentHeader layout");

// Environment bundle e: the environment's radiance along its direction omega both ways, and the
// density of either among the directions a point's hemisphere uses, p_r (Eq. 2: q(d) + q(-d)).
struct BidirEnvironmentBundle {
    vec3 radianceForward; // L_e(omega)
    float pdfForward;     // p_r(omega)
    vec3 radianceBackward; // L_e(-omega)
    float pdfBackward;     // p_r(-omega)
};
BL_STATIC_ASSERT(sizeof(BidirEnvironmentBundle) == 32, "BidirEnvironmentBundle layout");

BL_NAMESPACE_END
#endif
