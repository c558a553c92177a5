// Benchmarks of the implicit engine core: CPU polygonisation of convolution
// creatures (dense vs culled, throughput against the machine's measured FMA
// peak) and BlobTree instantiation + flattening speed.
#include <chrono>
#include <cmath>
#include <cstdio>
#include <random>
#include <thread>

#include "core/blobtree/compile.h"
#include "app/cli/bench/bench.h"
#include "core/poly/polygonizer.h"

namespace {

using namespace animorph;
using animorph::bench::Row;

#if defined(__x86_64__) && defined(__GNUC__) && !defined(__clang__) && !defined(__SANITIZE_ADDRESS__)
#define ANIMORPH_BENCH_CLONES __attribute__((target_clones("arch=x86-64-v4", "arch=x86-64-v3", "default")))
#else
#define ANIMORPH_BENCH_CLONES
#endif

// 12 independent FMA chains of 16 lanes: enough to hide FMA latency.
typedef float Lanes16 __attribute__((vector_size(64)));
__attribute__((optimize("fp-contract=fast"))) ANIMORPH_BENCH_CLONES
float fmaChains(long iterations, float seed) {
  Lanes16 acc[12];
  for (int k = 0; k < 12; ++k) acc[k] = (Lanes16){} + (seed + 0.01f * float(k));
  const Lanes16 a = (Lanes16){} + 0.9999999f, b = (Lanes16){} + 1e-7f;
  for (long i = 0; i < iterations; ++i) {
#pragma GCC unroll 12
    for (int k = 0; k < 12; ++k) acc[k] = acc[k] * a + b;
  }
  float s = 0.0f;
  for (int k = 0; k < 12; ++k)
    for (int j = 0; j < 16; ++j) s += acc[k][j];
  return s;
}

// Achievable single-precision GFLOP/s with 2 threads (FMA = 2 flop).
double measurePeakGflops() {
  const long iters = 4000000;
  volatile float sink = 0.0f;
  double best = 0.0;
  for (int rep = 0; rep < 3; ++rep) {
    auto t0 = std::chrono::steady_clock::now();
    float r[2];
    std::thread th([&] { r[1] = fmaChains(iters, 1.0f); });
    r[0] = fmaChains(iters, 2.0f);
    th.join();
    double s = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
    sink = sink + r[0] + r[1];
    best = std::max(best, 2.0 * double(iters) * 12 * 16 * 2 / s / 1e9);
  }
  (void)sink;
  return best;
}

// A seeded "creature": a wavy spine of half the segments, the rest as limbs
// and a neck branching off it, all inside the unit cube.
BlobTree creature(int n, unsigned seed) {
  std::mt19937 rng(seed);
  std::uniform_real_distribution<float> u(-1.0f, 1.0f);
  BlobTree tree;
  tree.threshold = FloatTrack(1.0f);
  tree.root = makeBlobNode(NodeType::Blend, 1, "body");
  int id = 2;
  auto add = [&](glm::vec3 a, glm::vec3 b, float r) {
    BlobNode s = makeBlobNode(NodeType::ConvSegment, id++);
    s.vec3Param("a") = Vec3Track(a);
    s.vec3Param("b") = Vec3Track(b);
    s.floatParam("radius") = FloatTrack(r);
    s.floatParam("sharpness") = FloatTrack(12.0f);
    tree.root.children.push_back(s);
  };
  int spine = std::max(2, n / 2);
  std::vector<glm::vec3> joints;
  for (int i = 0; i <= spine; ++i) {
    float x = -0.35f + 0.7f * float(i) / float(spine);
    joints.push_back({x, 0.05f * std::sin(6.0f * x) + 0.02f * u(rng), 0.04f * std::cos(5.0f * x)});
  }
  for (int i = 0; i < spine; ++i) add(joints[size_t(i)], joints[size_t(i + 1)], 0.05f + 0.015f * u(rng));
  int rest = n - spine;
  while (rest > 0) {
    glm::vec3 p = joints[size_t(std::uniform_int_distribution<int>(0, spine)(rng))];
    glm::vec3 dir = glm::normalize(glm::vec3(0.3f * u(rng), -0.8f + 0.3f * u(rng), 0.9f * u(rng)));
    int len = std::min(rest, 3);
    for (int k = 0; k < len; ++k) {
      glm::vec3 q = p + 0.1f * dir;
      q = glm::clamp(q, glm::vec3(-0.45f), glm::vec3(0.45f));
      add(p, q, 0.03f + 0.01f * u(rng));
      p = q;
      dir = glm::normalize(dir + 0.3f * glm::vec3(u(rng), u(rng), u(rng)));
    }
    rest -= len;
  }
  return tree;
}

// ~68 flop per (point, convolution segment) pair, divisions and sqrt counted as one.
constexpr double kFlopPerPair = 68.0;

PolygonizeResult polygonizeCube(const FieldProgram& prog, int res, bool cull) {
  PolygonizeSettings s;
  s.resolution = res;
  s.culling = cull;
  Bounds b;
  b.add(glm::vec3(-0.5f));
  b.add(glm::vec3(0.5f));
  s.bounds = b;
  s.threads = 2;
  auto r = polygonize(prog, s);
  return r.ok() ? std::move(*r) : PolygonizeResult{};
}

std::vector<Row> runPoly(const animorph::bench::Options& opt) {
  std::vector<Row> rows;
  double peak = measurePeakGflops();
  std::string load = "?";
  if (FILE* f = std::fopen("/proc/loadavg", "r")) {
    char buf[64] = {};
    if (std::fgets(buf, sizeof buf, f)) load = std::string(buf).substr(0, std::string(buf).find(' '));
    std::fclose(f);
  }
  rows.push_back({"machine peak (FMA loop, 2 threads)", peak, "GFLOP/s", "",
                  "measured in this run; load average " + load});
  std::vector<int> sizes = opt.quick ? std::vector<int>{64} : std::vector<int>{64, 128, 256};
  for (int n : {20, 60}) {
    FieldProgram prog = compileFieldProgram(creature(n, 1234u + unsigned(n)), 0.0);
    for (int res : sizes) {
      int reps = res >= 256 ? 1 : (res >= 128 ? 3 : 5);
      PolygonizeResult d, c;
      double msDense = animorph::bench::medianMs(reps, [&] { d = polygonizeCube(prog, res, false); });
      double msCull = animorph::bench::medianMs(reps, [&] { c = polygonizeCube(prog, res, true); });
      std::string tag = "N=" + std::to_string(n) + " " + std::to_string(res) + "^3";
      char note[160];
      std::snprintf(note, sizeof note, "%zu tris, %zu/%zu blocks culled", c.mesh.triangleCount(), c.stats.blocksCulled,
                    c.stats.blocksTotal);
      rows.push_back({tag + " dense", msDense, "ms", "", std::to_string(d.mesh.triangleCount()) + " tris"});
      rows.push_back({tag + " culled", msCull, "ms", "", note});
      rows.push_back({tag + " speed-up", msDense / msCull, "ratio", "", "dense / culled"});
      double gfDense = double(d.stats.primitiveEvaluations) * kFlopPerPair / (msDense * 1e6);
      double gfCull = double(c.stats.primitiveEvaluations) * kFlopPerPair / (msCull * 1e6);
      rows.push_back({tag + " dense throughput", gfDense / peak, "of peak", "",
                      std::to_string(int(gfDense)) + " GFLOP/s field math"});
      rows.push_back({tag + " culled throughput", gfCull / peak, "of peak", "",
                      std::to_string(int(gfCull)) + " GFLOP/s field math"});
      if (d.mesh.indices != c.mesh.indices) rows.push_back({tag + " MISMATCH dense vs culled", 1, "!", "", ""});
    }
  }
  {
    FieldProgram prog = compileFieldProgram(creature(40, 4242u), 0.0);
    PolygonizeResult r;
    double ms128 = animorph::bench::medianMs(opt.quick ? 3 : 5, [&] { r = polygonizeCube(prog, 128, true); });
    rows.push_back({"N=40 128^3 culled", ms128, "ms", "<= 25 ms", std::to_string(r.mesh.triangleCount()) + " tris"});
    if (!opt.quick) {
      double ms256 = animorph::bench::medianMs(3, [&] { r = polygonizeCube(prog, 256, true); });
      rows.push_back({"N=40 256^3 culled", ms256, "ms", "<= 120 ms", std::to_string(r.mesh.triangleCount()) + " tris"});
      rows.push_back({"N=40 cost 256^3 / 128^3", ms256 / ms128, "ratio", "<= 5x", "8x the cells"});
    }
  }
  {
    // A 2,000-node animated tree: 400 frames (keyed translation and rotation)
    // each holding 4 convolution segments with keyed end points and radii.
    BlobTree tree;
    tree.root = makeBlobNode(NodeType::Blend, 1, "root");
    int id = 2;
    for (int f = 0; f < 400; ++f) {
      BlobNode frame = makeBlobNode(NodeType::Frame, id++);
      frame.vec3Param("translation").setKey(0.0, glm::vec3(0.001f * float(f), 0, 0));
      frame.vec3Param("translation").setKey(1.0, glm::vec3(0.001f * float(f), 0.1f, 0));
      frame.quatParam("rotation").setKey(1.0, glm::angleAxis(0.5f, glm::vec3(0, 1, 0)));
      for (int k = 0; k < 4; ++k) {
        BlobNode s = makeBlobNode(NodeType::ConvSegment, id++);
        s.vec3Param("a").setKey(1.0, glm::vec3(0.01f * float(k), 0.1f, 0));
        s.vec3Param("b") = Vec3Track(glm::vec3(0.01f * float(k), 0.05f, 0.02f));
        s.vec3Param("b").setKey(2.0, glm::vec3(0.01f * float(k), 0.2f, 0.02f));
        s.floatParam("radius") = FloatTrack(0.02f);
        s.floatParam("radius").setKey(1.0, 0.03f);
        frame.children.push_back(s);
      }
      tree.root.children.push_back(frame);
    }
    size_t nodes = tree.root.subtreeSize() - 1;
    int iterations = 0;
    auto t0 = std::chrono::steady_clock::now();
    double elapsed = 0.0;
    size_t sink = 0;
    while (elapsed < (opt.quick ? 0.2 : 1.0)) {
      FieldProgram p = compileFieldProgram(tree, 0.01 * iterations);
      sink += p.ops.size();
      ++iterations;
      elapsed = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
    }
    double nodesPerSec = double(nodes) * iterations / elapsed;
    rows.push_back({"2000-node tree instantiate+flatten", nodesPerSec, "nodes/s", ">= 20000/s",
                    std::to_string(iterations / elapsed).substr(0, 6) + " trees/s (" + std::to_string(nodes) +
                        " nodes, " + std::to_string(sink / size_t(iterations)) + " ops)"});
  }
  return rows;
}

}  // namespace

ANIMORPH_BENCH("poly", "CPU polygoniser and BlobTree flattening (convolution creatures)", runPoly);
