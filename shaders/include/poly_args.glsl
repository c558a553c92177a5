// What follows each scan, as one invocation: scan totals -> counters, overflow
// flags and indirect arguments, so the frame runs without CPU read-back. On any
// overflow the draw has no indices (nothing truncated is ever drawn); the host
// reads the counters, grows the buffers and redoes the frame. Used by
// poly_args.comp (after the multi-group scan) and poly_scan_single.comp.

// After the block scan: active block count -> dispatch of the fine passes, one workgroup per
// active block in rows of P.gridCells.w (fineSlot()).
void argsAfterBlocks(uint activeCount) {
  control[AM_CTL_ACTIVE] = activeCount;
  if (activeCount > P.modes.w) control[AM_CTL_OVERFLOW] |= AM_OVERFLOW_BLOCKS;
  uint n = min(activeCount, P.modes.w), width = max(P.gridCells.w, 1u);
  control[AM_CTL_DISPATCH] = min(n, width);
  control[AM_CTL_DISPATCH + 1] = (n + width - 1u) / width;
  control[AM_CTL_DISPATCH + 2] = 1u;
}

// After the count scan: vertex and triangle totals -> indexed indirect draw, normals dispatch.
void argsAfterCounts(uint vertices, uint triangles) {
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
