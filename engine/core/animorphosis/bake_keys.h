#pragma once
// Key-frame animorphosis: the generic tree C baked into a plain key-framed
// BlobTree over [t0, t1] (an actor like any other, editable further). For each
// parameter, keys sit at the union of the key times of p_A and p_B (mapped
// through their clip timings) and of the node's s curve, inside [t0, t1];
// each key holds p_C = (1 - s) p_A + s p_B and its product-rule derivative
// dp_C/dt = (1 - s) p_A' + s p_B' + s' (p_B - p_A), and cubic Hermite-Ferguson
// interpolation runs between keys: exact at every key, at most nA + nB + ns
// keys per parameter (without clip loops). Quaternions are keyed by slerp
// (slerped between keys). A bridged blend / union / hyper-blend pair becomes a
// hyper-blend with q keyed the same way (q = 64 stands for the union, so at t1
// it is a hyper-blend, not B's exact union). Before t0 the tree holds C(t0),
// after t1 C(t1).
#include <atomic>
#include <functional>
#include <string>

#include "core/animorphosis/animorphosis_timing.h"
#include "core/animorphosis/generic_tree.h"

namespace animorph {

struct BakeKeysSettings {
  int samplesPerInterval = 8;  // points between two keys where the bake is compared with the live C
  // Called after each node of C is baked with (nodes done, nodes of C), on the baking thread.
  std::function<void(size_t done, size_t total)> progress;
  // Polled before every channel (a parameter, or one control point of a list): once true, the
  // bake stops within one channel's work and returns cancelled = true with an empty tree.
  const std::atomic<bool>* cancel = nullptr;
};

struct BakeKeysReport {
  size_t parameters = 0;         // baked channels (each control point of a list counts as one)
  size_t keys = 0;               // keys in all of them
  int mostKeys = 0;              // most keys on one channel
  int mostKeysBound = 0;         // nA + nB + ns of that channel
  bool withinBound = true;       // every channel has <= nA + nB + ns keys (nA, nB: distinct key times)
  double largestDeviation = 0.0;  // largest |baked - live| between keys (parameter units; quaternions: radians)
  std::string largestDeviationAt;  // which node and parameter
};

struct BakedAnimorphosis {
  BlobTree tree;  // ids 1..n in pre-order, the same order as instantiateGeneric
  BakeKeysReport report;
  bool cancelled = false;  // stopped by BakeKeysSettings::cancel: tree and report are empty
};

// Needs endSec > startSec. Works on any generic tree buildGenericTree made.
BakedAnimorphosis bakeKeyframes(const GenericTree& c, const AnimorphosisTiming& timing,
                                const BakeKeysSettings& settings = {});

}  // namespace animorph
