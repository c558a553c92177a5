#include "polygonizer_rig.h"

#include <catch2/catch.hpp>

#include "gpu_fixture.h"

namespace animorph::test {

PolygonizerRig::PolygonizerRig() : ctx(makeTestContext()) {
  auto p = gpu::GpuPolygonizer::create(*ctx);
  INFO(p.error());
  REQUIRE(p.ok());
  poly = std::move(*p);
}

TriangleMesh PolygonizerRig::polygonizeAndRead(const gpu::GpuField& f, const gpu::GpuPolygonizeSettings& s,
                                               const gpu::GpuPreparedFrame* prepared, gpu::GpuPolygonizeStats& stats) {
  auto st = poly->polygonize(f, s, prepared);
  INFO(st.error());
  REQUIRE(st.ok());
  stats = *st;
  auto m = poly->readBack();
  INFO(m.error());
  REQUIRE(m.ok());
  return std::move(*m);
}

}  // namespace animorph::test
