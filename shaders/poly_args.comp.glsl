#version 450
#extension GL_GOOGLE_include_directive : require
// One invocation between passes: turns scan totals into counters, overflow
// flags and indirect arguments, so the frame runs without CPU read-back.
//   AM_ARGS_AFTER_BLOCKS: active block count -> dispatch of the fine passes
//   AM_ARGS_AFTER_COUNTS: vertex and triangle totals -> indexed indirect draw, normals dispatch
// On any overflow the draw has no indices (nothing truncated is ever drawn);
// the host reads the counters, grows the buffers and redoes the frame.
#include "poly_common.glsl"

layout(local_size_x = 1) in;
layout(push_constant) uniform ArgsPush { uvec4 pc; };  // x: AM_ARGS_*

void main() {
  if (pc.x == AM_ARGS_AFTER_BLOCKS) {
    uint activeCount = control[AM_CTL_SCAN_TOTAL];
    control[AM_CTL_ACTIVE] = activeCount;
    if (activeCount > P.modes.w) control[AM_CTL_OVERFLOW] |= AM_OVERFLOW_BLOCKS;
    control[AM_CTL_DISPATCH] = min(activeCount, P.modes.w);
    control[AM_CTL_DISPATCH + 1] = 1u;
    control[AM_CTL_DISPATCH + 2] = 1u;
  } else {
    uint vertices = control[AM_CTL_SCAN_TOTAL];
    uint triangles = control[AM_CTL_SCAN_TOTAL + 1];
    control[AM_CTL_VERTICES] = vertices;
    control[AM_CTL_TRIANGLES] = triangles;
    if (vertices > P.caps.x) control[AM_CTL_OVERFLOW] |= AM_OVERFLOW_VERTICES;
    if (triangles > P.caps.y) control[AM_CTL_OVERFLOW] |= AM_OVERFLOW_TRIANGLES;
    bool ok = control[AM_CTL_OVERFLOW] == 0u;
    control[AM_CTL_DRAW] = ok ? 3u * triangles : 0u;  // indexCount
    control[AM_CTL_DRAW + 1] = 1u;                    // instanceCount
    control[AM_CTL_DRAW + 2] = 0u;                    // firstIndex
    control[AM_CTL_DRAW + 3] = 0u;                    // vertexOffset
    control[AM_CTL_DRAW + 4] = 0u;                    // firstInstance
    // Normals pass: four vertices per invocation over the mesh's vertices (none on overflow).
    uint perGroup = 4u * uint(AM_POLY_WG_NORMALS);
    control[AM_CTL_NORMALS] = ok ? (vertices + perGroup - 1u) / perGroup : 0u;
    control[AM_CTL_NORMALS + 1] = 1u;
    control[AM_CTL_NORMALS + 2] = 1u;
  }
}
