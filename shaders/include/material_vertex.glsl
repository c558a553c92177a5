// The material streams of a character mesh (texture coordinates, COLOR_0) and
// their pass-through to the fragment stage (include/mesh_material.glsl). Shared
// by mesh.vert and transition.vert; include after shared_constants.h.
layout(location = AM_VERTEX_TEXCOORD0) in vec2 inTexcoord0;
layout(location = AM_VERTEX_COLOR0) in vec4 inColor0;

layout(location = 2) out vec2 outTexcoord0;
layout(location = 3) out vec4 outColor0;
// The colour the material's base fades into (rgb, linear) and how far (a): a
// transition's stand-in colour at its alpha (transition.vert); (0, 0, 0, 0) else.
layout(location = 4) out vec4 outStandinColor;

// Passes the vertex's material inputs on unchanged, with no stand-in colour. A
// transition writes outStandinColor after calling this.
void amPassMaterial() {
  outTexcoord0 = inTexcoord0;
  outColor0 = inColor0;
  outStandinColor = vec4(0.0);
}
