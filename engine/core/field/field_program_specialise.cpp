// FieldProgram, part 2 of 4: a program specialised to a region (the primitives and operators that
// can matter there), as the polygoniser asks per block.
#include "core/field/field_program.h"

#include <algorithm>
#include <functional>
#include <atomic>
#include <cassert>
#include <cmath>
#include <limits>

#include "core/field/convolution_segment.h"
#include "core/field/field_program_detail.h"
#include "core/field/potential.h"

namespace animorph {

using field_detail::boxesOverlap;
using field_detail::distToSegment;

// ------------------------------------------------------------------ specialising

void FieldProgram::specialiseAll(ActiveProgram& out) const {
  out.ops = ops;
  out.indices.clear();
  for (FieldOp& op : out.ops) {
    op.subtreeBegin = 0;  // no colour provenance (see colourProvenance)
    if (op.code == OpCode::Prims) {
      uint32_t off = uint32_t(out.indices.size());
      for (uint32_t k = 0; k < op.count; ++k) out.indices.push_back(op.first + k);
      op.first = off;
    }
  }
  out.primitiveCount = primitiveBounds.size();
}

namespace {
// In an ActiveProgram, an op's subtreeBegin (an index of the whole program, meaningless there and
// read by no evaluator) carries the colour walk's provenance instead (field/surface_color.h): bits
// 30-31 a rule, bits 0-29 one plus the index of the whole program's op whose empty colour (its
// colour where none of its primitives contributes) the op has where the rule applies. Rule 1:
// everywhere (a constant standing for a dropped subtree); 2: where every operand's weight is 0 (a
// Sum whose first operand, exactly 0, was dropped); 3: where its value is <= 0 (the one operand
// left of a Sum whose other, zero operands were dropped, the first among them). 0: none.
uint32_t colourProvenance(uint32_t rule, uint32_t op) { return rule << 30 | ((op + 1) & 0x3fffffffu); }

// The last op of the one operand left of Sum ops[origin] (its other operands, the first among them,
// were exactly 0 and dropped): where its value is <= 0 every weight of the Sum was 0, and the
// Sum's colour was its first operand's, the Sum's empty colour. This rule covers any the op had
// (they fire only where its value is <= 0 too), but a constant's own colour where it is above 0.
void markLoneOperand(FieldOp& last, uint32_t origin) {
  if (last.code == OpCode::Const && last.emptyValue > 0.0f) return;
  last.subtreeBegin = colourProvenance(last.code == OpCode::Const ? 1 : 3, origin);
}
}  // namespace

void FieldProgram::specialise(const std::vector<uint32_t>& active, ActiveProgram& out) const {
  out.ops.clear();
  out.indices.clear();
  out.primitiveCount = active.size();
  // One forward walk that jumps over every subtree holding no active primitive: its cost is the
  // ops it emits plus the active primitives, not the size of the whole program. The primitives
  // of ops i..e are the global ids [primsBefore_[i], primsBefore_[e + 1]).
  //
  // Operands that are exactly zero (a constant 0, primitives none of which is active) are dropped
  // from sums as they are emitted: a + 0 is a, and the other operands keep their order, so the
  // values are the same and the evaluation runs fewer ops.
  //
  // The colour walk (field/surface_color.h) must give the whole program's colours: where a dropped
  // operand or subtree would have decided the colour, each op's subtreeBegin says whose empty
  // colour it is (colourProvenance). The field ignores it.
  struct Operand {
    uint32_t start;  // first op of the operand in out.ops
    bool zero;       // a single op pushing exactly 0
  };
  thread_local std::vector<Operand> operands;
  thread_local std::vector<uint32_t> mapStarts;
  operands.clear();
  mapStarts.clear();
  auto emitted = [&](const FieldOp& op, uint32_t origin) {
    const uint32_t at = uint32_t(out.ops.size()) - 1;
    switch (op.code) {
      case OpCode::Const: operands.push_back({at, op.emptyValue == 0.0f}); return;
      case OpCode::Prims: operands.push_back({at, op.count == 0}); return;
      case OpCode::BeginMap: mapStarts.push_back(at); return;
      case OpCode::EndMap:  // the map's subtree is one operand, from its BeginMap
        operands.back() = {mapStarts.back(), false};
        mapStarts.pop_back();
        return;
      default: break;
    }
    const size_t n = op.count, base = operands.size() - n;
    const uint32_t first = operands[base].start;
    if (op.code == OpCode::Sum) {
      size_t zeros = 0;
      for (size_t k = base; k < operands.size(); ++k) zeros += operands[k].zero;
      if (zeros > 0) {
        const bool firstZero = operands[base].zero;
        out.ops.pop_back();  // the Sum, emitted again below if still needed
        // Operands before the first zero stay where they are (the first is often a long chain).
        size_t k = base, kept = 0;
        for (; !operands[k].zero; ++k) ++kept;
        uint32_t w = operands[k].start;
        for (; k < operands.size(); ++k) {
          uint32_t end = k + 1 < operands.size() ? operands[k + 1].start : uint32_t(out.ops.size());
          if (operands[k].zero) continue;
          for (uint32_t j = operands[k].start; j < end; ++j) out.ops[w + (j - operands[k].start)] = out.ops[j];
          w += end - operands[k].start;
          ++kept;
        }
        out.ops.resize(w);
        operands.resize(base);
        if (kept == 0) {
          FieldOp c;
          c.code = OpCode::Const;
          c.emptyValue = 0.0f;
          c.subtreeBegin = colourProvenance(1, origin);
          out.ops.push_back(c);
          operands.push_back({first, true});
        } else {
          if (kept > 1) {
            FieldOp sum = op;
            sum.count = uint32_t(kept);
            if (firstZero) sum.subtreeBegin = colourProvenance(2, origin);
            out.ops.push_back(sum);
          } else if (firstZero) {
            markLoneOperand(out.ops.back(), origin);
          }
          operands.push_back({first, false});
        }
        return;
      }
    }
    operands.resize(base);
    operands.push_back({first, false});
  };
  size_t cursor = 0;
  for (size_t i = 0; i < ops.size();) {
    uint32_t e = outermostEnd_[i];
    // Only leaves and map openings start subtrees; operators close them.
    bool startsSubtree = ops[i].code == OpCode::Prims || ops[i].code == OpCode::BeginMap;
    if (startsSubtree) {
      while (cursor < active.size() && active[cursor] < primsBefore_[i]) ++cursor;
    }
    if (startsSubtree && !(cursor < active.size() && active[cursor] < primsBefore_[e + 1])) {
      FieldOp c;
      c.code = OpCode::Const;
      c.emptyValue = ops[e].emptyValue;
      c.subtreeBegin = colourProvenance(1, e);
      out.ops.push_back(c);
      emitted(c, e);
      i = e + 1;
      continue;
    }
    FieldOp op = ops[i];
    op.subtreeBegin = 0;
    if (op.code == OpCode::Prims) {
      while (cursor < active.size() && active[cursor] < op.primBegin) ++cursor;
      uint32_t off = uint32_t(out.indices.size());
      while (cursor < active.size() && active[cursor] < op.primBegin + op.count) {
        out.indices.push_back(op.first + (active[cursor] - op.primBegin));
        ++cursor;
      }
      op.first = off;
      op.count = uint32_t(out.indices.size()) - off;
    }
    out.ops.push_back(op);
    emitted(op, uint32_t(i));
    ++i;
  }
}

void FieldProgram::primitivesReaching(const Bounds& box, std::vector<uint32_t>& out,
                                      const std::vector<uint32_t>* candidates) const {
  out.clear();
  glm::vec3 c = box.center();
  float half = 0.5f * box.diagonal();
  auto test = [&](uint32_t g) {
    const PrimitiveBound& b = primitiveBounds[g];
    if (!boxesOverlap(b.box, box)) return;
    if (distToSegment(c, b.a, b.b) > b.radius + half) return;
    out.push_back(g);
  };
  if (candidates) {
    for (uint32_t g : *candidates) test(g);
  } else {
    for (uint32_t g = 0; g < primitiveBounds.size(); ++g) test(g);
  }
}

}  // namespace animorph
