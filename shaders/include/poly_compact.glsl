// Active-block compaction: active block b gets slot s, its exclusive prefix in
// the block scan (block order, so the output is deterministic); the slot's
// block position is recorded (packBlockCoord) and blockSlot[] maps blocks to
// slots (AM_POLY_NONE: inactive, or beyond the block capacity, which the args
// report as an overflow). Used by poly_compact.comp and poly_scan_single.comp.
void compactBlock(uint b, bool live, uint s) {
  uint slot = AM_POLY_NONE;
  if (live && s < P.modes.w) {
    activeBlocks[s] = packBlockCoord(blockCoord(b));
    slot = s;
  }
  blockSlot[b] = slot;
}
