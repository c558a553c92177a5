#version 450
#extension GL_GOOGLE_include_directive : require
// One invocation after a multi-group scan (poly_scan.comp): the arguments of
// poly_args.glsl from the scan total.
//   AM_ARGS_AFTER_BLOCKS: active block count -> dispatch of the fine passes
//   AM_ARGS_AFTER_COUNTS: vertex and triangle totals -> indexed indirect draw, normals dispatch
#include "poly_common.glsl"
#include "poly_args.glsl"

layout(local_size_x = 1) in;
layout(push_constant) uniform ArgsPush { uvec4 pc; };  // x: AM_ARGS_*

void main() {
  if (pc.x == AM_ARGS_AFTER_BLOCKS) argsAfterBlocks(control[AM_CTL_SCAN_TOTAL]);
  else argsAfterCounts(control[AM_CTL_SCAN_TOTAL], control[AM_CTL_SCAN_TOTAL + 1]);
}
