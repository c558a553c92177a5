// Exclusive prefix sum of one uvec2 per invocation across a workgroup of
// AM_POLY_WG_SCAN invocations (Hillis-Steele); used by poly_scan.comp and
// poly_scan_single.comp.
shared uvec2 sums[AM_POLY_WG_SCAN];

// Returns this invocation's exclusive prefix; the workgroup's total is sums[AM_POLY_WG_SCAN - 1] after it.
uvec2 workgroupExclusive(uvec2 mine) {
  uint t = gl_LocalInvocationID.x;
  sums[t] = mine;
  barrier();
  for (uint d = 1u; d < AM_POLY_WG_SCAN; d <<= 1) {
    uvec2 add = t >= d ? sums[t - d] : uvec2(0u);
    barrier();
    sums[t] += add;
    barrier();
  }
  return sums[t] - mine;
}
