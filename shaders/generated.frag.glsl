#version 450
#extension GL_GOOGLE_include_directive : require
// Viewport shading of a GPU-generated mesh (generated.vert): its vertices' surface colour as the
// base colour where the colour pass made one (as a CPU mesh's vertex colours), else the draw's tone.
#include "frame.glsl"

#include "mesh_push.glsl"
#include "mesh_shading.glsl"

layout(location = 0) in vec3 inWorldPos;
layout(location = 1) in vec3 inWorldNormal;
layout(location = 2) in vec4 inSurfaceColor;
layout(location = 0) out vec4 outColor;

void main() {
  outColor = inSurfaceColor.a > 0.5 ? amShadeMeshBase(inWorldPos, inWorldNormal, inSurfaceColor.rgb)
                                    : amShadeMesh(inWorldPos, inWorldNormal);
}
