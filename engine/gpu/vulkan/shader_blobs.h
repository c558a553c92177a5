#pragma once
// SPIR-V of the shaders in shaders/, compiled and embedded at build time
// (cmake/AnimorphShaders.cmake).
#include <cstdint>
#include <span>

namespace animorph::gpu {

// The SPIR-V words of shader `name` (file name without ".glsl", e.g. "mesh.vert");
// an empty span when no such shader was built.
std::span<const uint32_t> shaderBlob(const char* name);

}  // namespace animorph::gpu
