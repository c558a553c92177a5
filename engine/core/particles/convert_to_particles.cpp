#include "core/particles/convert_to_particles.h"

#include "core/field/surface_color.h"

#include <algorithm>
#include <cmath>
#include <string>

#include <tbb/parallel_for.h>
#include <tbb/task_arena.h>

#include "core/field/potential.h"
#include "core/field/surface_color.h"

namespace animorph {

namespace {

// Points spaced `spacing` over box, centred in it (at least one per axis); shifted by shift
// spacings (each in [0, 1)), with one more point per axis so that the box stays covered.
SampleLattice gridOver(const Bounds& box, float spacing, glm::vec3 shift = glm::vec3(0.0f)) {
  SampleLattice g;
  g.spacing = spacing;
  glm::vec3 size = box.size();
  const bool shifted = shift != glm::vec3(0.0f);
  for (int a = 0; a < 3; ++a) g.dims[a] = std::max(1, int(std::ceil(size[a] / spacing))) + (shifted ? 1 : 0);
  g.origin = box.center() - 0.5f * spacing * glm::vec3(g.dims - 1) + (shifted ? spacing * (shift - 0.5f) : glm::vec3(0.0f));
  return g;
}

// inside[x + dims.x (y + dims.y z)] = f(point) >= 0, one z slice per task.
std::vector<uint8_t> insideOfField(const FieldProgram& shape, const SampleLattice& g) {
  std::vector<uint8_t> inside(g.size(), 0);
  tbb::parallel_for(0, g.dims.z, [&](int z) {
    thread_local FieldEvaluator evaluator;
    Bounds slice;
    slice.add(g.point(0, 0, z));
    slice.add(g.point(g.dims.x - 1, g.dims.y - 1, z));
    std::vector<uint32_t> reaching;
    shape.primitivesReaching(slice, reaching);
    ActiveProgram active;
    shape.specialise(reaching, active);
    size_t n = size_t(g.dims.x) * size_t(g.dims.y);
    std::vector<float> x(n), y(n), zz(n), f(n);
    for (int j = 0; j < g.dims.y; ++j)
      for (int i = 0; i < g.dims.x; ++i) {
        glm::vec3 p = g.point(i, j, z);
        size_t k = size_t(i) + size_t(g.dims.x) * size_t(j);
        x[k] = p.x;
        y[k] = p.y;
        zz[k] = p.z;
      }
    evaluator.evaluate(shape, active, x.data(), y.data(), zz.data(), int(n), f.data());
    for (size_t k = 0; k < n; ++k) inside[size_t(z) * n + k] = f[k] >= 0.0f;
  });
  return inside;
}

size_t countSet(const std::vector<uint8_t>& v) { return size_t(std::count(v.begin(), v.end(), uint8_t(1))); }

bool cancelled(const ConvertToParticlesSettings& s) { return s.cancel && s.cancel->load(); }

// The lattice with the fewest points inside the shape that are still at least n, within 1 % above
// n when it can be found: a search on the spacing h, bracketed then bisected (the count falls as h
// grows, in steps of one point or a few -- a symmetric shape's points cross its boundary together
// -- while the lattice's dimensions stay the same, of a whole layer when they change), repeated
// with the lattice shifted by fractions of a spacing when a step jumps over the 1 % window. At
// most 30 lattices per shift. Fewer than n only when no spacing tried reaches n. h: the estimate
// in, the spacing chosen out.
std::vector<uint8_t> latticeNear(const ParticleShape& shape, const Bounds& box, size_t n, float& h, SampleLattice& lattice,
                                 const ConvertToParticlesSettings& s) {
  std::vector<uint8_t> best;
  size_t bestCount = 0;
  float bestH = h;
  auto better = [&](size_t c) {
    if (best.empty()) return true;
    if ((c >= n) != (bestCount >= n)) return c >= n;
    return c >= n ? c < bestCount : c > bestCount;
  };
  auto within = [&](size_t c) { return c >= n && double(c) <= 1.01 * double(n); };
  const glm::vec3 shifts[] = {{0.0f, 0.0f, 0.0f},   {0.5f, 0.5f, 0.5f},    {0.25f, 0.5f, 0.75f}, {0.5f, 0.0f, 0.0f},
                              {0.0f, 0.5f, 0.0f},   {0.0f, 0.0f, 0.5f},    {0.75f, 0.25f, 0.5f}, {0.25f, 0.25f, 0.25f}};
  const float h0 = h;
  for (const glm::vec3& shift : shifts) {
    float lo = 0.0f, hi = 0.0f;  // spacings giving >= n and < n (0: none yet)
    float trial = bestCount >= n && bestH > 0.0f ? bestH : h0;
    for (int iter = 0; iter < 30 && !cancelled(s); ++iter) {
      SampleLattice g = gridOver(box, trial, shift);
      std::vector<uint8_t> inside = shape.insideOnLattice(g);
      const size_t c = countSet(inside);
      if (better(c)) {
        best = std::move(inside);
        bestCount = c;
        bestH = trial;
        lattice = g;
      }
      if (within(bestCount)) break;
      if (c >= n) lo = std::max(lo, trial);
      else hi = hi > 0.0f ? std::min(hi, trial) : trial;
      if (lo > 0.0f && hi > 0.0f) {
        if (hi - lo <= 1e-6f * hi) break;  // a step over the window at this shift
        trial = 0.5f * (lo + hi);
      } else {
        trial *= float(std::cbrt(c ? double(c) / double(n) : 8.0)) * (c >= n ? 1.0f : 0.99f);
      }
    }
    if (within(bestCount) || cancelled(s)) break;
  }
  h = bestH;
  return best;
}

// 1. The shape's volume on a coarse grid, then the lattice of spacing h with about s.count points
// inside. Fails when nothing is inside; on cancel returns success with the lattice unset.
Status particleLattice(const ParticleShape& shape, const ConvertToParticlesSettings& s, const Bounds& box, int cells,
                       float& h, SampleLattice& lattice, std::vector<uint8_t>& occupied) {
  glm::vec3 size = box.size();
  double boxVolume = double(std::max(size.x, 1e-6f)) * std::max(size.y, 1e-6f) * std::max(size.z, 1e-6f);
  SampleLattice coarse = gridOver(box, float(std::cbrt(boxVolume / (cells / 4))));
  double volume = double(countSet(shape.insideOnLattice(coarse))) * std::pow(double(coarse.spacing), 3);
  if (volume <= 0.0)
    return Error{"convert to particles: nothing inside the shape at a " + std::to_string(coarse.dims.x) + "x" +
                 std::to_string(coarse.dims.y) + "x" + std::to_string(coarse.dims.z) + " grid"};
  if (s.progress) s.progress(0.1f);
  h = float(std::cbrt(volume / s.count));
  occupied = latticeNear(shape, box, size_t(s.count), h, lattice, s);
  if (cancelled(s)) return Status::success();
  if (countSet(occupied) == 0) return Error{"convert to particles: no lattice point inside the shape"};
  return Status::success();
}

// The potential of unit-intensity points of radius R at the occupied lattice points, at every
// point of the fine grid.
std::vector<float> particlePotential(const SampleLattice& fine, const SampleLattice& lattice,
                                     const std::vector<uint8_t>& occupied, float h, float R, float stiffness) {
  std::vector<float> potential(fine.size(), 0.0f);
  float r2 = R * R;
  tbb::parallel_for(0, fine.dims.z, [&](int z) {
    for (int y = 0; y < fine.dims.y; ++y)
      for (int x = 0; x < fine.dims.x; ++x) {
        glm::vec3 p = fine.point(x, y, z);
        glm::vec3 lo = (p - glm::vec3(R) - lattice.origin) / h, hi = (p + glm::vec3(R) - lattice.origin) / h;
        glm::ivec3 a = glm::max(glm::ivec3(glm::ceil(lo)), glm::ivec3(0));
        glm::ivec3 b = glm::min(glm::ivec3(glm::floor(hi)), lattice.dims - 1);
        float sum = 0.0f;
        for (int k = a.z; k <= b.z; ++k)
          for (int j = a.y; j <= b.y; ++j)
            for (int i = a.x; i <= b.x; ++i) {
              if (!occupied[lattice.index(i, j, k)])
                continue;
              glm::vec3 d = p - lattice.point(i, j, k);
              float d2 = glm::dot(d, d);
              if (d2 >= r2) continue;
              float t = 1.0f - d2 / r2;
              sum += powStiffness(t, stiffness);
            }
        potential[fine.index(x, y, z)] = sum;
      }
  });
  return potential;
}

// The particles as a Blend of Point nodes (ids from 2), one per occupied lattice point.
void particleTree(const SampleLattice& lattice, const std::vector<uint8_t>& occupied, size_t count, float R,
                  float intensity, const ConvertToParticlesSettings& s, BlobTree& tree) {
  tree.threshold = FloatTrack(s.threshold);
  tree.root = makeBlobNode(NodeType::Blend, 1, "particles");
  tree.root.children.reserve(count);
  int id = 2;
  for (int k = 0; k < lattice.dims.z; ++k)
    for (int j = 0; j < lattice.dims.y; ++j)
      for (int i = 0; i < lattice.dims.x; ++i) {
        if (!occupied[lattice.index(i, j, k)])
          continue;
        BlobNode p = makeBlobNode(NodeType::Point, id, "p" + std::to_string(id - 2));
        ++id;
        p.vec3Param("center") = Vec3Track(lattice.point(i, j, k));
        p.floatParam("radius") = FloatTrack(R);
        p.floatParam("intensity") = FloatTrack(intensity);
        p.floatParam("stiffness") = FloatTrack(s.stiffness);
        tree.root.children.push_back(std::move(p));
      }
}

// The conversion proper (in the settings' task arena): the lattice, the calibration of the points'
// intensity on a fine grid (as many fine cells inside the particles as inside the shape), the tree
// and the report. On cancel returns success with out unfinished.
Status convertInArena(const ParticleShape& shape, const ConvertToParticlesSettings& s, const Bounds& box, int cells,
                      ConvertToParticlesResult& out) {
  auto progress = [&](float f) {
    if (s.progress) s.progress(f);
  };
  float h = 0.0f;
  SampleLattice lattice;
  std::vector<uint8_t> occupied;
  if (Status st = particleLattice(shape, s, box, cells, h, lattice, occupied); !st || cancelled(s)) return st;
  const size_t count = countSet(occupied);
  progress(0.3f);
  if (cancelled(s)) return Status::success();
  // 2. Calibration: potential of unit-intensity points on a fine grid around the shape.
  float R = s.radiusFactor * h;
  Bounds grown = box;
  grown.add(box.min - glm::vec3(R));
  grown.add(box.max + glm::vec3(R));
  glm::vec3 gs = grown.size();
  SampleLattice fine = gridOver(grown, std::min(h * 0.5f, float(std::cbrt(double(gs.x) * gs.y * gs.z / cells))));
  std::vector<uint8_t> shapeInside = shape.insideOnLattice(fine);
  size_t target = countSet(shapeInside);
  if (target == 0) return Error{"convert to particles: nothing inside the shape on the calibration grid"};
  progress(0.5f);
  if (cancelled(s)) return Status::success();
  std::vector<float> potential = particlePotential(fine, lattice, occupied, h, R, s.stiffness);
  progress(0.9f);
  // 3. The intensity at which as many fine cells are inside the particles as inside the shape.
  std::vector<float> sorted = potential;
  std::nth_element(sorted.begin(), sorted.begin() + long(target - 1), sorted.end(), std::greater<float>());
  float sAt = sorted[target - 1];
  if (!(sAt > 0.0f))
    return Error{"convert to particles: the shape is too thin for " + std::to_string(s.count) + " particles"};
  float intensity = s.threshold / sAt;
  size_t particleCells = 0;
  for (float v : potential) particleCells += intensity * v >= s.threshold ? 1 : 0;
  double cell3 = std::pow(double(fine.spacing), 3);
  particleTree(lattice, occupied, count, R, intensity, s, out.tree);
  ConvertToParticlesReport& rep = out.report;
  rep.particles = count;
  rep.spacing = h;
  rep.radius = R;
  rep.intensity = intensity;
  rep.shapeVolume = double(target) * cell3;
  rep.particleVolume = double(particleCells) * cell3;
  progress(1.0f);
  return Status::success();
}

}  // namespace

Result<ParticleShape> fieldParticleShape(const FieldProgram& program) {
  if (program.unbounded()) return Error{"convert to particles: the shape is unbounded"};
  ParticleShape shape;
  shape.bounds = program.tightBounds();
  shape.insideOnLattice = [&program](const SampleLattice& g) { return insideOfField(program, g); };
  return shape;
}

Result<ConvertToParticlesResult> convertToParticles(const FieldProgram& program, const ConvertToParticlesSettings& s) {
  auto shape = fieldParticleShape(program);
  if (!shape) return Error{shape.error()};
  auto r = convertToParticles(*shape, s);
  if (!r) return r;
  // Each particle takes the shape's colour where it sits (field/surface_color.h); where that is the
  // clay tone (a shape without colours) the default stays, so such trees save as before.
  std::vector<BlobNode>& points = r->tree.root.children;
  std::vector<glm::vec3> centres(points.size());
  for (size_t i = 0; i < points.size(); ++i) centres[i] = points[i].vec3Param("center").evaluate(0.0);
  std::vector<glm::vec4> colors(points.size());
  SurfaceColorEvaluator().evaluate(program, centres.data(), centres.size(), colors.data(), s.threads);
  const glm::vec3 clay = srgbToLinear(kClayColorSrgb);
  for (size_t i = 0; i < points.size(); ++i)
    if (glm::any(glm::greaterThan(glm::abs(glm::vec3(colors[i]) - clay), glm::vec3(1e-5f))))
      points[i].vec3Param("color") = Vec3Track(linearToSrgb(glm::vec3(colors[i])));
  return r;
}

Result<ConvertToParticlesResult> convertToParticles(const ParticleShape& shape, const ConvertToParticlesSettings& s) {
  if (s.count < 1 || s.count > 1'000'000) return Error{"convert to particles: count " + std::to_string(s.count) +
                                                      " is not in 1..1000000"};
  if (!(s.radiusFactor >= 0.6f && s.radiusFactor <= 4.0f))
    return Error{"convert to particles: radius factor must be in [0.6, 4]"};
  if (!(s.threshold > 0.0f) || !(s.stiffness > 0.0f))
    return Error{"convert to particles: threshold and stiffness must be > 0"};
  Bounds box = shape.bounds;
  if (box.empty() || !(glm::length(box.size()) > 0.0f)) return Error{"convert to particles: the shape is empty"};
  int cells = std::max(1000, s.calibrationCells);
  tbb::task_arena arena(s.threads > 0 ? s.threads : tbb::task_arena::automatic);
  ConvertToParticlesResult out;
  Status status;
  arena.execute([&] { status = convertInArena(shape, s, box, cells, out); });
  if (!status) return Error{status.error()};
  if (cancelled(s)) {
    out.tree = BlobTree{};
    out.report = ConvertToParticlesReport{};
    out.report.cancelled = true;
  }
  return out;
}

}  // namespace animorph
