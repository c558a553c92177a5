// Viewport shading of meshes (mesh.frag, mesh_dither.frag): a headlight plus a
// key light over a little ambient, two-sided, readable on any base colour (like
// Maya's default shading); selection adds a rim. Needs frame.glsl and
// mesh_push.glsl first.
// base: the surface colour in linear light (mesh_material.glsl's, or pc.baseLinear.rgb).
vec4 amShadeMeshBase(vec3 worldPos, vec3 worldNormal, vec3 base) {
  if ((pc.flags & AM_DRAW_WIREFRAME) != 0u) return pc.color;
  vec3 v = normalize(frame.cameraPos.xyz - worldPos);
  vec3 n = worldNormal;
  float len = length(n);
  n = len > 1e-12 ? n / len : v;
  if (dot(n, v) < 0.0) n = -n;  // two-sided: back faces and flipped normals shade like front faces
  vec3 l = frame.keyLightDir.xyz;
  float head = max(dot(n, v), 0.0);
  float key = max(dot(n, l), 0.0);
  // x^40 by squaring: a pow is a log and an exp per pixel on a CPU device (llvmpipe).
  float s1 = max(dot(n, normalize(v + l)), 0.0), s2 = s1 * s1, s4 = s2 * s2, s8 = s4 * s4, s16 = s8 * s8;
  float spec = s16 * s16 * s8;
  vec3 lit = base * (0.10 + 0.60 * head + 0.45 * key) + vec3(0.06) * spec;
  if ((pc.flags & AM_DRAW_SELECTED) != 0u) {
    vec3 sel = frame.selectColor.rgb;  // linear
    float rim = (1.0 - head) * (1.0 - head);
    lit = mix(lit, sel * (0.3 + 0.7 * head), 0.25) + sel * rim * 0.8;
  }
  return vec4(pow(lit, vec3(1.0 / 2.2)), pc.color.a);
}

vec4 amShadeMesh(vec3 worldPos, vec3 worldNormal) {
  return amShadeMeshBase(worldPos, worldNormal, pc.baseLinear.rgb);  // pow(color, 2.2), taken once per draw
}
