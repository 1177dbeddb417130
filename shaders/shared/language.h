// What lets one header be both C++ and GLSL: in C++ the GLSL types are glm's, in
// namespace vitrum::gpu, and constants are constexpr.
#ifndef VITRUM_LANGUAGE_H
#define VITRUM_LANGUAGE_H

#ifdef __cplusplus
#include <cstdint>
#include <glm/glm.hpp>
namespace vitrum::gpu {
using vec2 = glm::vec2;
using vec3 = glm::vec3;
using vec4 = glm::vec4;
using uvec4 = glm::uvec4;
using uint = std::uint32_t;
}  // namespace vitrum::gpu
#define VITRUM_CONST constexpr
#define VITRUM_GPU_BEGIN namespace vitrum::gpu {
#define VITRUM_GPU_END }
#else
#define VITRUM_CONST const
#define VITRUM_GPU_BEGIN
#define VITRUM_GPU_END
#endif

#endif
