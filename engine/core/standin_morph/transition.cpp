#include "core/standin_morph/transition.h"

#include <algorithm>
#include <chrono>
#include <cmath>

#include <tbb/parallel_for.h>
#include <tbb/task_arena.h>

#include "core/field/surface_color.h"
#include "core/rig/morph_targets.h"
#include "core/rig/vertex_colors.h"
#include "core/standin/standin_colors.h"
#include "core/rig/pose.h"
#include "core/standin/character_pose.h"

namespace animorph {

FloatTrack smoothstepTrack() { return hermiteRampTrack(0.0f, 0.0f); }

namespace {

// The binding's colours (StandinBinding): segs and positions posed alike, projected the vertices'
// points on the stand-in. Nothing when c has no colour of its own.
void bindColors(const Character& c, std::vector<PosedSegment> segs, const Standin& s,
                const std::vector<glm::vec3>& positions, const std::vector<glm::vec3>& projected, StandinBinding& b) {
  b.vertexColors = characterVertexColors(c);
  if (b.vertexColors.size() != positions.size() || positions.empty()) {
    b.vertexColors.clear();
    return;
  }
  b.segmentColors = sampleSegmentColors(segs, positions.data(), b.vertexColors.data(), positions.size());
  for (size_t k = 0; k < segs.size(); ++k) segs[k].colors = b.segmentColors[k];
  const FieldProgram colors = standinProgram(s.kind, s.sharpness, splitSegmentsForColor(segs));
  b.standinColors.resize(projected.size());
  SurfaceColorEvaluator().evaluate(colors, projected.data(), projected.size(), b.standinColors.data());
}

}  // namespace

StandinBinding bindToStandin(const Character& c, const Standin& s, const AnimationClip* clip, float clipTimeSec,
                             const ProjectionSettings& settings) {
  StandinBinding b;
  const CharacterPose pose = poseCharacter(c, clip, clipTimeSec, glm::mat4(1.0f));
  const auto segs = poseStandin(s, pose.globals, glm::mat4(1.0f));
  const FieldProgram prog = standinProgram(s.kind, s.sharpness, segs);
  const size_t n = pose.positions.size();
  std::vector<glm::vec3> projected(n), nrm(n);
  b.stats = projectOntoField(prog, segs, pose.positions.data(), n, projected.data(), nrm.data(), settings);
  b.offsets.resize(n);
  b.standinNormals.resize(n);
  tbb::parallel_for(size_t(0), n, [&](size_t i) {
    const glm::mat3 w(pose.vertexMatrices[i]);
    const float det = glm::determinant(w);
    if (std::abs(det) < 1e-20f) {
      // Degenerate skinning (zero scale): the bind-space move cannot be recovered.
      b.offsets[i] = glm::vec3(0.0f);
      b.standinNormals[i] = glm::vec3(0, 1, 0);
      return;
    }
    b.offsets[i] = glm::inverse(w) * (projected[i] - pose.positions[i]);
    if (!pose.morphOffsets.empty()) b.offsets[i] += pose.morphOffsets[i];  // from the unmorphed bind shape
    const glm::vec3 nb = glm::transpose(w) * nrm[i];  // normals map back by the transpose
    const float l = glm::length(nb);
    b.standinNormals[i] = l > 0.0f ? nb / l : glm::vec3(0, 1, 0);
  });
  bindColors(c, segs, s, pose.positions, projected, b);
  return b;
}

void transitionColors(const StandinBinding& b, const std::vector<float>& alpha, std::vector<glm::vec4>& out) {
  if (!b.hasColors() || alpha.size() != b.vertexColors.size()) {
    out.clear();
    return;
  }
  out.resize(alpha.size());
  for (size_t i = 0; i < alpha.size(); ++i) {
    const float a = std::clamp(alpha[i], 0.0f, 1.0f);
    out[i] = b.vertexColors[i] + a * (b.standinColors[i] - b.vertexColors[i]);
  }
}

void transitionEasingTable(const FloatTrack& easing, std::vector<float>& table) {
  constexpr int kLut = kTransitionEasingIntervals;
  table.resize(kLut + 1);
  for (int k = 0; k <= kLut; ++k) table[size_t(k)] = std::clamp(easing.evaluate(float(k) / kLut), 0.0f, 1.0f);
  table[0] = 0.0f;
  table[kLut] = 1.0f;
}

void transitionAlphas(double u, const FloatTrack& easing, const std::vector<float>& weightMap, float shift, bool expand,
                      size_t n, std::vector<float>& alpha) {
  alpha.resize(n);
  const float uc = float(std::clamp(u, 0.0, 1.0));
  auto ease = [&](float x) { return std::clamp(easing.evaluate(std::clamp(x, 0.0f, 1.0f)), 0.0f, 1.0f); };
  if (weightMap.size() != n || !(shift > 0.0f)) {
    float a = ease(uc);
    if (uc <= 0.0f) a = 0.0f;
    if (uc >= 1.0f) a = 1.0f;
    std::fill(alpha.begin(), alpha.end(), expand ? 1.0f - a : a);
    return;
  }
  // The easing sampled once per call (a table), then read per vertex.
  constexpr int kLut = kTransitionEasingIntervals;
  std::vector<float> lut;
  transitionEasingTable(easing, lut);
  const float s = std::min(shift, 0.999f);
  const float dur = 1.0f - s;
  for (size_t i = 0; i < n; ++i) {
    const float m = std::clamp(weightMap[i], 0.0f, 1.0f);
    const float x = std::clamp((uc - s * (1.0f - m)) / dur, 0.0f, 1.0f) * kLut;
    const int k = std::min(kLut - 1, int(x));
    const float a = lut[k] + (lut[k + 1] - lut[k]) * (x - float(k));
    alpha[i] = expand ? 1.0f - a : a;
  }
}

TransitionStats evaluateTransition(const Character& c, const StandinBinding& binding,
                                   const std::vector<glm::mat4>& globals, const glm::mat4& root,
                                   const std::vector<float>& alpha, const FieldProgram* posedField,
                                   const std::vector<PosedSegment>* posedSegments, const TransitionSettings& settings,
                                   std::vector<glm::vec3>& positions, std::vector<glm::vec3>& normals) {
  const auto t0 = std::chrono::steady_clock::now();
  TransitionStats st;
  const std::vector<int> meshNodes = c.meshNodes();
  size_t total = 0;
  for (int node : meshNodes) total += c.meshes[size_t(c.nodes[size_t(node)].mesh)].vertexCount();
  positions.resize(total);
  normals.resize(total);
  const bool bound = binding.offsets.size() == total && binding.standinNormals.size() == total;
  tbb::task_arena arena(settings.threads > 0 ? settings.threads : tbb::task_arena::automatic);
  size_t first = 0;
  std::vector<glm::vec3> morphedP, morphedN;
  for (size_t mi = 0; mi < meshNodes.size(); ++mi) {
    const int node = meshNodes[mi];
    const Mesh& mesh = c.meshes[size_t(c.nodes[size_t(node)].mesh)];
    const auto joints = jointMatrices(c, node, globals);
    // Blend shapes: the morphed bind shape at alpha = 0, the binding's target (from the unmorphed one) at 1.
    const bool morphed = mi < settings.morphWeights.size() && !mesh.morphTargets.empty() &&
                         hasActiveMorph(settings.morphWeights[mi]);
    if (morphed) morphMesh(mesh, settings.morphWeights[mi], morphedP, morphedN);
    const glm::mat4 model = root * globals[size_t(node)];
    const glm::mat3 modelNormal = glm::transpose(glm::inverse(glm::mat3(model)));
    const size_t n = mesh.vertexCount();
    const glm::vec3* P0 = mesh.positions.data();
    const glm::vec3* P = morphed ? morphedP.data() : P0;
    const glm::vec3* N = mesh.normals.size() == n ? (morphed ? morphedN.data() : mesh.normals.data()) : nullptr;
    const glm::vec3* dP = bound ? binding.offsets.data() + first : nullptr;
    const glm::vec3* nT = bound ? binding.standinNormals.data() + first : nullptr;
    const float* A = alpha.size() == total ? alpha.data() + first : nullptr;
    glm::vec3* outP = positions.data() + first;
    glm::vec3* outN = normals.data() + first;
    // Joint matrices as 3x4 (the fourth row of an affine matrix is unused):
    // accumulating the same products in the same order as skinMesh gives the
    // same bits for the rows that matter, with a quarter less work.
    struct Affine { glm::vec3 c[4]; };
    std::vector<Affine> J(joints.size());
    for (size_t j = 0; j < joints.size(); ++j)
      for (int k = 0; k < 4; ++k) J[j].c[k] = glm::vec3(joints[j][k]);
    const size_t jointCount = J.size();
    const bool skinned = !mesh.joints0.empty();
    const bool second = !mesh.joints1.empty();
    arena.execute([&] {
      tbb::parallel_for(tbb::blocked_range<size_t>(0, n, 2048), [&](const tbb::blocked_range<size_t>& r) {
        for (size_t v = r.begin(); v != r.end(); ++v) {
          glm::vec3 c0(0.0f), c1(0.0f), c2(0.0f), c3(0.0f);
          if (!skinned) {
            const Affine& m = jointCount ? J[0] : Affine{{glm::vec3(1, 0, 0), glm::vec3(0, 1, 0), glm::vec3(0, 0, 1), glm::vec3(0.0f)}};
            c0 = m.c[0]; c1 = m.c[1]; c2 = m.c[2]; c3 = m.c[3];
          } else {
            auto accumulate = [&](const glm::uvec4& j, const glm::vec4& w) {
              for (int k = 0; k < 4; ++k)
                if (w[k] != 0.0f && j[k] < jointCount) {
                  const Affine& m = J[j[k]];
                  c0 += w[k] * m.c[0];
                  c1 += w[k] * m.c[1];
                  c2 += w[k] * m.c[2];
                  c3 += w[k] * m.c[3];
                }
            };
            accumulate(mesh.joints0[v], mesh.weights0[v]);
            if (second) accumulate(mesh.joints1[v], mesh.weights1[v]);
          }
          const float a = A ? A[v] : 0.0f;
          glm::vec3 p = P[v];
          glm::vec3 nb = N ? N[v] : glm::vec3(0, 1, 0);
          if (dP && a != 0.0f) {
            p = glm::mix(p, P0[v] + dP[v], a);
            // nlerp's normalisation is left to the final one (a linear map in between).
            const glm::vec3 nl = glm::mix(nb, nT[v], a);
            nb = glm::dot(nl, nl) > 1e-24f ? nl : nT[v];
          }
          const glm::vec3 pm = (c0 * p.x + c1 * p.y) + (c2 * p.z + c3 * 1.0f);  // glm's order
          outP[v] = glm::vec3(model * glm::vec4(pm, 1.0f));
          // Inverse-transpose up to a positive factor: the cofactor matrix (three
          // cross products, no division), sign-corrected; normalised below.
          const glm::mat3 cof(glm::cross(c1, c2), glm::cross(c2, c0), glm::cross(c0, c1));
          const float det = glm::dot(c0, cof[0]);
          glm::vec3 nw = modelNormal * (cof * nb);
          if (det < 0.0f) nw = -nw;
          const float l = glm::length(nw);
          outN[v] = l > 0.0f ? nw / l : glm::vec3(0, 1, 0);
        }
      });
    });
    first += n;
  }
  // Re-projection onto the posed field near the end of the transition.
  if (posedField && posedSegments && alpha.size() == total && settings.reprojectFrom < 1.0f) {
    std::vector<uint32_t> idx;
    for (size_t i = 0; i < total; ++i)
      if (alpha[i] > settings.reprojectFrom) idx.push_back(uint32_t(i));
    if (!idx.empty()) {
      std::vector<glm::vec3> in(idx.size()), out(idx.size()), nf(idx.size());
      for (size_t k = 0; k < idx.size(); ++k) in[k] = positions[idx[k]];
      ProjectionSettings ps = settings.reprojection;
      ps.threads = settings.threads;
      const ProjectionStats pst = projectOntoField(*posedField, *posedSegments, in.data(), in.size(), out.data(),
                                                   nf.data(), ps);
      st.reprojected = idx.size();
      st.reprojectFailures = pst.failures;
      const float r0 = settings.reprojectFrom;
      for (size_t k = 0; k < idx.size(); ++k) {
        const size_t i = idx[k];
        const float x = std::clamp((alpha[i] - r0) / (1.0f - r0), 0.0f, 1.0f);
        const float beta = alpha[i] >= 1.0f ? 1.0f : x * x * (3.0f - 2.0f * x);
        positions[i] = glm::mix(positions[i], out[k], beta);
        const glm::vec3 nn = glm::mix(normals[i], nf[k], beta);
        const float l = glm::length(nn);
        if (l > 1e-12f) normals[i] = nn / l;
      }
    }
  }
  st.milliseconds = std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - t0).count();
  return st;
}

}  // namespace animorph
