// Screen-door transparency: true where a pixel of a draw at opacity pc.color.a is
// not drawn (4x4 Bayer threshold at or above the opacity; AM_DRAW_DITHER_INVERT
// uses 1 - threshold, so draws at opacities o and 1 - o cover complementary pixels).
// Needs transition_constants.h and mesh_push.glsl first.
const float kBayer4[16] = float[](0.0, 8.0, 2.0, 10.0, 12.0, 4.0, 14.0, 6.0, 3.0, 11.0, 1.0, 9.0, 15.0, 7.0, 13.0, 5.0);

bool amDitheredOut() {
  ivec2 q = ivec2(gl_FragCoord.xy) & 3;
  float threshold = (kBayer4[q.y * 4 + q.x] + 0.5) / 16.0;
  if ((pc.flags & AM_DRAW_DITHER_INVERT) != 0u) threshold = 1.0 - threshold;
  return !(pc.color.a > threshold);
}
