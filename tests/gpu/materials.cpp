// Materials on lavapipe: a glTF quad with a 2x2 texture of four known colours
// renders those colours at its four quarters; factors, several materials per
// mesh, vertex colours and an undecodable texture (factor colour) as the file
// says; a mesh without colour keeps the viewport grey exactly.
#include <catch2/catch.hpp>

#include <cstdlib>

#include "gpu_fixture.h"
#include "core/io/gltf_import.h"
#include "gpu/render/mesh_cache.h"
#include "gpu/render/scene_renderer.h"
#include "util/temp_dir.h"
#include "util/textured_fixtures.h"

using namespace animorph;
using namespace animorph::gpu;
using animorph::test::pixelAt;
using animorph::test::TexturedQuadOptions;

namespace {

const glm::vec4 kBackground{0.1f, 0.1f, 0.1f, 1.0f};

OrbitCamera frontCamera() {
  OrbitCamera c;
  c.target = glm::vec3(0.0f);
  c.yawRad = 0.0f;
  c.pitchRad = 0.0f;
  c.distanceM = 4.0f;
  return c;
}

Scene sceneOf(const GpuMesh* mesh) {
  Scene s;
  s.options.background = kBackground;
  s.options.grid = false;
  s.options.axisIndicator = false;
  MeshDraw d;
  d.mesh = mesh;
  s.meshes.push_back(d);
  return s;
}

// Saves img when ANIMORPH_TEST_IMAGES names a folder (to look at).
void keep(const RgbaImage& img, const char* name) {
  if (const char* dir = std::getenv("ANIMORPH_TEST_IMAGES")) (void)writePng(std::string(dir) + "/" + name, img);
}

// The channel k of p exceeds the other two by margin (or, for two channels a and b, both exceed the third).
bool dominant(glm::u8vec4 p, int k, int margin = 60) {
  return int(p[k]) > int(p[(k + 1) % 3]) + margin && int(p[k]) > int(p[(k + 2) % 3]) + margin;
}
bool yellowish(glm::u8vec4 p) { return int(p.r) > int(p.b) + 60 && int(p.g) > int(p.b) + 60; }

std::shared_ptr<const Character> load(const std::string& path) {
  auto c = importGltf(path);
  INFO(c.error());
  REQUIRE(c);
  return std::make_shared<const Character>(std::move(*c));
}

}  // namespace

TEST_CASE("a textured glTF quad renders its texture's four colours at its four quarters", "[gpu][materials]") {
  auto ctx = test::makeTestContext();
  auto target = test::makeSceneTarget(*ctx, 160, 160);
  test::TempDir tmp;
  auto ch = load(test::writeTexturedQuad(tmp.path().string()));
  MeshCache cache(*ctx);
  const GpuMesh* mesh = cache.get(ch, 0);
  INFO(cache.lastError());
  REQUIRE(mesh);
  REQUIRE(mesh->parts().size() == 1);
  CHECK(mesh->parts()[0].texture != VK_NULL_HANDLE);
  CHECK(cache.textureCount() == 1);
  const OrbitCamera cam = frontCamera();
  const RgbaImage& img = test::renderScene(target, cam, sceneOf(mesh));
  keep(img, "textured_quad.png");
  const glm::u8vec4 tl = pixelAt(img, cam, {-0.5f, 0.5f, 0}), tr = pixelAt(img, cam, {0.5f, 0.5f, 0});
  const glm::u8vec4 bl = pixelAt(img, cam, {-0.5f, -0.5f, 0}), br = pixelAt(img, cam, {0.5f, -0.5f, 0});
  INFO("top left " << int(tl.r) << "," << int(tl.g) << "," << int(tl.b) << "  top right " << int(tr.r) << ","
                   << int(tr.g) << "," << int(tr.b) << "  bottom left " << int(bl.r) << "," << int(bl.g) << ","
                   << int(bl.b) << "  bottom right " << int(br.r) << "," << int(br.g) << "," << int(br.b));
  CHECK(dominant(tl, 0));  // red
  CHECK(dominant(tr, 1));  // green
  CHECK(dominant(bl, 2));  // blue
  CHECK(yellowish(br));    // yellow
  CHECK(int(tl.r) > 150);  // lit, not darkened: the headlight faces the quad
  CHECK(ctx->validationErrorCount() == 0);
}

TEST_CASE("a factor tints the texture, a second material draws its own colour, an undecodable texture "
          "falls back to the factor",
          "[gpu][materials]") {
  auto ctx = test::makeTestContext();
  auto target = test::makeSceneTarget(*ctx, 200, 120);
  test::TempDir tmp, tmp2;
  TexturedQuadOptions o;
  o.secondPrimitive = true;
  o.factor = {0.0f, 1.0f, 1.0f, 1.0f};  // removes the red: the red texel goes black, yellow goes green
  auto ch = load(test::writeTexturedQuad(tmp.path().string(), o));
  MeshCache cache(*ctx);
  const GpuMesh* mesh = cache.get(ch, 0);
  REQUIRE(mesh);
  REQUIRE(mesh->parts().size() == 2);
  OrbitCamera cam = frontCamera();
  cam.target = {1.25f, 0.0f, 0.0f};
  cam.distanceM = 6.0f;
  const RgbaImage& img = test::renderScene(target, cam, sceneOf(mesh));
  keep(img, "factor_and_second_material.png");
  const glm::u8vec4 tl = pixelAt(img, cam, {-0.5f, 0.5f, 0}), br = pixelAt(img, cam, {0.5f, -0.5f, 0});
  const glm::u8vec4 second = pixelAt(img, cam, {2.5f, 0.0f, 0});
  CHECK(int(tl.r) + int(tl.g) + int(tl.b) < 90);  // red x (0, 1, 1): dark
  CHECK(dominant(br, 1));                          // yellow x (0, 1, 1): green
  CHECK(dominant(second, 2));                      // the blue material of the second primitive
  CHECK(ctx->validationErrorCount() == 0);

  o = TexturedQuadOptions{};
  o.image = TexturedQuadOptions::Image::CorruptFile;
  o.factor = {0.9f, 0.5f, 0.1f, 1.0f};
  auto broken = load(test::writeTexturedQuad(tmp2.path().string(), o));
  const GpuMesh* bm = cache.get(broken, 0);
  REQUIRE(bm);
  CHECK(bm->parts()[0].texture == VK_NULL_HANDLE);
  const OrbitCamera front = frontCamera();
  const RgbaImage& img2 = test::renderScene(target, front, sceneOf(bm));
  keep(img2, "undecodable_texture.png");
  for (glm::vec3 p : {glm::vec3(-0.5f, 0.5f, 0), glm::vec3(0.5f, -0.5f, 0)}) {
    const glm::u8vec4 px = pixelAt(img2, front, p);
    CHECK(int(px.r) > int(px.g) + 30);  // orange everywhere: the factor, no texels
    CHECK(int(px.g) > int(px.b) + 30);
  }
}

TEST_CASE("a minified one-texel checker is drawn in its mean grey through the mipmaps, not aliased",
          "[gpu][materials]") {
  auto ctx = test::makeTestContext();
  auto target = test::makeSceneTarget(*ctx, 160, 160);
  // A 2 x 2 m quad with a 256 x 256 checker of single black and white texels, seen from 12 m:
  // about 25 pixels across, ten texels a pixel.
  constexpr int kSide = 256;
  auto pixels = std::make_shared<std::vector<uint8_t>>(size_t(kSide) * kSide * 4, uint8_t(255));
  for (int y = 0; y < kSide; ++y)
    for (int x = 0; x < kSide; ++x)
      if ((x + y) % 2) std::fill_n(pixels->data() + (size_t(y) * kSide + size_t(x)) * 4, 3, uint8_t(0));
  Character c;
  Mesh m;
  m.positions = {{-1, -1, 0}, {1, -1, 0}, {1, 1, 0}, {-1, 1, 0}};
  m.normals.assign(4, {0, 0, 1});
  m.texcoords0 = {{0, 1}, {1, 1}, {1, 0}, {0, 0}};
  m.indices = {0, 1, 2, 0, 2, 3};
  m.material = 0;
  c.meshes.push_back(m);
  TextureImage t;
  t.name = "checker";
  t.width = t.height = kSide;
  t.rgba = pixels;
  c.textures.push_back(t);
  Material mat;
  mat.baseColorTexture = 0;
  c.materials.push_back(mat);
  c.nodes.push_back(Node{});
  c.nodes[0].mesh = 0;
  c.roots = {0};
  auto ch = std::make_shared<const Character>(c);
  MeshCache cache(*ctx);
  const GpuMesh* mesh = cache.get(ch, 0);
  INFO(cache.lastError());
  REQUIRE(mesh);
  OrbitCamera cam = frontCamera();
  cam.distanceM = 12.0f;
  const RgbaImage& img = test::renderScene(target, cam, sceneOf(mesh));
  keep(img, "minified_checker.png");
  // The quad's inner pixels: without mipmaps each takes the one or four texels nearest its
  // centre (black, white or anything between, a moire); with them, the checker's mean.
  int lo = 255, hi = 0;
  for (float x = -0.7f; x <= 0.7f; x += 0.1f)
    for (float y = -0.7f; y <= 0.7f; y += 0.1f) {
      const glm::u8vec4 p = pixelAt(img, cam, {x, y, 0});
      lo = std::min(lo, int(p.g));
      hi = std::max(hi, int(p.g));
    }
  INFO("green over the quad " << lo << ".." << hi);
  CHECK(hi - lo <= 12);
  CHECK(lo > 60);    // not the black texels
  CHECK(hi < 240);   // nor the white ones
  CHECK(ctx->validationErrorCount() == 0);
}

TEST_CASE("vertex colours colour a mesh, and a mesh without colour keeps the viewport grey exactly",
          "[gpu][materials]") {
  auto ctx = test::makeTestContext();
  auto target = test::makeSceneTarget(*ctx, 160, 120);
  Character c;
  c.meshes.push_back(test::twoQuadMesh());
  c.materials.push_back(Material{});  // white, untextured: no colour of its own
  c.meshes[0].material = 0;
  c.nodes.push_back(Node{});
  c.nodes[0].mesh = 0;
  c.roots = {0};
  Character coloured = c;
  coloured.meshes[0].colors.assign(coloured.meshes[0].vertexCount(), glm::vec4(0.1f, 0.8f, 0.2f, 1.0f));
  auto plain = std::make_shared<const Character>(c);
  auto green = std::make_shared<const Character>(coloured);
  MeshCache cache(*ctx);
  const GpuMesh* pm = cache.get(plain, 0);
  const GpuMesh* gm = cache.get(green, 0);
  REQUIRE(pm);
  REQUIRE(gm);
  CHECK_FALSE(pm->parts()[0].coloured);
  CHECK(gm->hasVertexColors());
  OrbitCamera cam = frontCamera();
  cam.distanceM = 6.0f;
  Scene s = sceneOf(pm);
  const RgbaImage withMaterial = test::renderScene(target, cam, s);
  s.meshes[0].materials = false;
  const RgbaImage grey = test::renderScene(target, cam, s);
  CHECK(withMaterial.pixels == grey.pixels);  // today's look, to the byte
  const glm::u8vec4 g = pixelAt(grey, cam, {-1, 0, 0});
  CHECK(std::abs(int(g.r) - int(g.g)) <= 1);
  CHECK(std::abs(int(g.g) - int(g.b)) <= 1);
  const RgbaImage& img = test::renderScene(target, cam, sceneOf(gm));
  keep(img, "vertex_colours.png");
  CHECK(dominant(pixelAt(img, cam, {-1, 0, 0}), 1));
  CHECK(ctx->validationErrorCount() == 0);
}
