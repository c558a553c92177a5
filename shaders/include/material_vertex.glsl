// The material streams of a character mesh (texture coordinates, COLOR_0) and
// their pass-through to the fragment stage (include/mesh_material.glsl). Shared
// by mesh.vert and transition.vert; include after shared_constants.h.
layout(location = AM_VERTEX_TEXCOORD0) in vec2 inTexcoord0;
layout(location = AM_VERTEX_COLOR0) in vec4 inColor0;

layout(location = 2) out vec2 outTexcoord0;
layout(location = 3) out vec4 outColor0;

// Passes the vertex's material inputs on unchanged. A transition that blends the
// colour towards its stand-in's writes outColor0 after calling this.
void amPassMaterial() {
  outTexcoord0 = inTexcoord0;
  outColor0 = inColor0;
}
