// Lets one header compile as GLSL 4.60 and as C++20 (with GLM), so host and device share
// struct layouts, constants and functions instead of writing them twice.
//
// Rules for shared code: float literals carry an `f` suffix (valid in both), scalars in structs are
// `uint`/`float`/`int`, vec3 is followed by a 4-byte scalar so std430 and C++ agree, and every struct
// gets a static_assert on its size in the C++ half (BL_STATIC_ASSERT is empty in GLSL).
#ifndef BL_SHARED_PRELUDE_H
#define BL_SHARED_PRELUDE_H

#ifdef __cplusplus
#include <cstddef>
#include <cstdint>
#include <glm/glm.hpp>

#define BL_NAMESPACE_BEGIN                                                                         \
    namespace bl::shader {                                                                         \
    using namespace glm;                                                                           \
    using uint = std::uint32_t;
#define BL_NAMESPACE_END }
#define BL_CONST inline constexpr
#define BL_INLINE inline
#define BL_INOUT(T) T&
#define BL_OUT(T) T&
#define BL_STATIC_ASSERT(cond, msg) static_assert(cond, msg)
#else
#define BL_NAMESPACE_BEGIN
#define BL_NAMESPACE_END
#define BL_CONST const
#define BL_INLINE
#define BL_INOUT(T) inout T
#define BL_OUT(T) out T
#define BL_STATIC_ASSERT(cond, msg)
#endif

BL_NAMESPACE_BEGIN
BL_CONST float kPi = 3.14159265358979323846f;
BL_CONST float kInvPi = 0.31830988618379067154f;
BL_CONST float kTwoPi = 6.28318530717958647692f;
BL_NAMESPACE_END

#endif
