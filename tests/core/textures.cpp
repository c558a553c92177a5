#include <catch2/catch.hpp>

#include <filesystem>
#include <fstream>

#include "core/io/assimp_import.h"
#include "core/io/gltf_export.h"
#include "core/io/gltf_import.h"
#include "core/io/texture_decode.h"
#include "core/paint/weights_from_texture.h"
#include "core/rig/texture_image.h"
#include "util/temp_dir.h"
#include "util/test_skip.h"
#include "util/textured_fixtures.h"

using namespace animorph;
using animorph::test::TempDir;
using animorph::test::TexturedQuadOptions;

namespace {

glm::ivec4 texelAt(const TextureImage& t, int x, int y) {
  const uint8_t* p = t.rgba->data() + (size_t(y) * t.width + x) * 4;
  return {p[0], p[1], p[2], p[3]};
}

bool anyWarningHas(const Character& c, const std::string& a, const std::string& b) {
  for (const auto& w : c.report.warnings)
    if (w.find(a) != std::string::npos && w.find(b) != std::string::npos) return true;
  return false;
}

}  // namespace

TEST_CASE("textures: a PNG decodes to its exact texels and a JPEG to within its compression error", "[textures]") {
  const std::vector<uint8_t> px = test::quadTexelBytes();
  const std::vector<uint8_t> png = test::encodePng(2, 2, px), jpg = test::encodeJpeg(2, 2, px);
  REQUIRE(!png.empty());
  REQUIRE(!jpg.empty());
  auto p = decodeTextureImage(png.data(), png.size(), "quad.png");
  REQUIRE(p);
  CHECK(p->width == 2);
  CHECK(p->height == 2);
  for (int i = 0; i < 4; ++i) {
    const auto& e = test::kQuadTexels[size_t(i)];
    CHECK(texelAt(*p, i % 2, i / 2) == glm::ivec4(e[0], e[1], e[2], e[3]));
  }
  auto j = decodeTextureImage(jpg.data(), jpg.size(), "quad.jpg");
  REQUIRE(j);
  REQUIRE(j->width == 2);
  // JPEG: no alpha (255), and 4:2:0 chroma over a 2x2 block smears the hues; the brightest
  // channel of each texel still is the one of the source colour.
  for (int i = 0; i < 4; ++i) {
    const glm::ivec4 got = texelAt(*j, i % 2, i / 2);
    CHECK(got.a == 255);
    CHECK(got.r + got.g + got.b > 120);
  }
}

TEST_CASE("textures: corrupt, empty and oversized images are refused, naming the image and the reason", "[textures]") {
  const std::vector<uint8_t> junk = {0x89, 'P', 'N', 'G', 1, 2, 3, 4, 5};
  auto a = decodeTextureImage(junk.data(), junk.size(), "skin.png");
  REQUIRE_FALSE(a);
  CHECK(a.error().find("skin.png: cannot decode: ") == 0);
  CHECK(a.error().size() > std::string("skin.png: cannot decode: ").size());
  auto b = decodeTextureImage(nullptr, 0, "empty.png");
  REQUIRE_FALSE(b);
  CHECK(b.error().find("empty.png") != std::string::npos);
  // A PNG header that declares 10000 x 10000 pixels (100 Mpixels) is refused before decoding.
  std::vector<uint8_t> big = test::encodePng(2, 2, test::quadTexelBytes());
  REQUIRE(big.size() > 24);
  const uint32_t side = 10000;
  for (int k = 0; k < 4; ++k) big[16 + k] = big[20 + k] = uint8_t(side >> (24 - 8 * k));
  auto c = decodeTextureImage(big.data(), big.size(), "huge.png");
  REQUIRE_FALSE(c);
  INFO(c.error());
  CHECK(c.error().find("huge.png: 10000 x 10000 pixels is over the texture budget") == 0);
  // Files outside the character's folder are not read.
  TempDir tmp;
  auto d = loadTextureFile(tmp.path().string(), "../outside.png");
  REQUIRE_FALSE(d);
  CHECK(d.error().find("outside the character file's folder") != std::string::npos);
  auto e = loadTextureFile(tmp.path().string(), "/etc/passwd");
  REQUIRE_FALSE(e);
  CHECK(e.error().find("absolute paths are not allowed") != std::string::npos);
}

TEST_CASE("textures: sampling follows the sampler's filter and wrap modes", "[textures]") {
  TextureImage t;
  t.width = t.height = 2;
  t.rgba = std::make_shared<const std::vector<uint8_t>>(test::quadTexelBytes());
  t.magFilter = TextureFilter::Nearest;
  t.wrapS = t.wrapT = TextureWrap::ClampToEdge;
  CHECK(sampleTexture(t, {0.25f, 0.25f}) == glm::vec4(1, 0, 0, 1));
  CHECK(sampleTexture(t, {0.75f, 0.75f}) == glm::vec4(1, 1, 0, 0));
  CHECK(sampleTexture(t, {5.0f, -3.0f}) == glm::vec4(0, 1, 0, 170.0f / 255.0f));  // clamped: top right
  t.wrapS = t.wrapT = TextureWrap::Repeat;
  CHECK(sampleTexture(t, {1.25f, 1.75f}) == glm::vec4(0, 0, 1, 85.0f / 255.0f));
  t.wrapS = TextureWrap::MirroredRepeat;
  CHECK(sampleTexture(t, {1.25f, 0.25f}) == glm::vec4(0, 1, 0, 170.0f / 255.0f));  // mirrored: x = 0.75
  t.magFilter = TextureFilter::Linear;
  t.wrapS = t.wrapT = TextureWrap::ClampToEdge;
  const glm::vec4 mid = sampleTexture(t, {0.5f, 0.5f});  // the average of all four
  CHECK(mid.r == Approx(0.5f));
  CHECK(mid.g == Approx(0.5f));
  CHECK(mid.b == Approx(0.25f));
  CHECK(mid.a == Approx((255 + 170 + 85 + 0) / 4.0f / 255.0f));
}

TEST_CASE("textures: a glTF base colour texture is decoded with its sampler, coordinates and factor", "[textures]") {
  for (auto kind : {TexturedQuadOptions::Image::PngFile, TexturedQuadOptions::Image::JpegFile,
                    TexturedQuadOptions::Image::Embedded}) {
    TempDir tmp;
    TexturedQuadOptions o;
    o.image = kind;
    o.factor = {0.5f, 1.0f, 1.0f, 1.0f};
    auto c = importGltf(test::writeTexturedQuad(tmp.path().string(), o));
    INFO((c ? std::string() : c.error()));
    REQUIRE(c);
    INFO("image kind " << int(kind));
    REQUIRE(c->materials.size() == 1);
    const Material& m = c->materials[0];
    CHECK(m.baseColorFactor == glm::vec4(0.5f, 1, 1, 1));
    CHECK(m.baseColorTextureEmbedded == (kind == TexturedQuadOptions::Image::Embedded));
    REQUIRE(m.baseColorTexture == 0);
    REQUIRE(c->textures.size() == 1);
    const TextureImage& t = c->textures[0];
    CHECK(t.valid());
    CHECK(t.width == 2);
    CHECK(t.magFilter == TextureFilter::Nearest);
    CHECK(t.wrapS == TextureWrap::ClampToEdge);
    if (kind != TexturedQuadOptions::Image::JpegFile) CHECK(texelAt(t, 1, 0) == glm::ivec4(0, 255, 0, 170));
    const Mesh& mesh = c->meshes.at(0);
    REQUIRE(mesh.texcoords0.size() == 4);
    CHECK(mesh.texcoords0[2] == glm::vec2(1, 1));
    REQUIRE(mesh.parts.size() == 1);
    CHECK(mesh.parts[0].indexCount == 6);
    CHECK(mesh.parts[0].material == 0);
  }
}

TEST_CASE("textures: KHR_texture_transform is applied to the coordinates and primitives keep their materials",
          "[textures]") {
  TempDir tmp;
  TexturedQuadOptions o;
  o.textureTransform = true;
  o.secondPrimitive = true;
  auto c = importGltf(test::writeTexturedQuad(tmp.path().string(), o));
  INFO((c ? std::string() : c.error()));
  REQUIRE(c);
  for (const auto& u : c->report.unsupported) CHECK(u.find("KHR_texture_transform") == std::string::npos);
  const Mesh& mesh = c->meshes.at(0);
  REQUIRE(mesh.texcoords0.size() == 8);
  CHECK(mesh.texcoords0[0] == glm::vec2(0.5f, 0.0f));  // offset (0.5, 0) + scale (0.5, 1) * (0, 0)
  CHECK(mesh.texcoords0[2] == glm::vec2(1.0f, 1.0f));  // 0.5 + 0.5 * 1
  CHECK(mesh.texcoords0[4] == glm::vec2(0.0f));        // the untextured primitive
  REQUIRE(mesh.parts.size() == 2);
  CHECK(mesh.parts[0].firstIndex == 0);
  CHECK(mesh.parts[1].firstIndex == 6);
  CHECK(mesh.parts[1].indexCount == 6);
  CHECK(mesh.parts[1].material == 1);
  CHECK(c->materials.at(1).baseColorTexture == -1);
  CHECK(c->materials.at(1).baseColorFactor.b == Approx(0.9f));
}

TEST_CASE("textures: the mipmap chain halves each level down to 1 x 1, averaging in linear light", "[textures]") {
  CHECK(textureLevelCount(1, 1) == 1);
  CHECK(textureLevelCount(256, 256) == 9);
  CHECK(textureLevelCount(5, 3) == 3);
  // A 4 x 2 image: black and white texels side by side, then a red row.
  TextureImage t;
  t.name = "chain";
  t.width = 4;
  t.height = 2;
  t.rgba = std::make_shared<std::vector<uint8_t>>(std::vector<uint8_t>{
      0, 0, 0, 255, 255, 255, 255, 255, 0, 0, 0, 255, 255, 255, 255, 0,          //
      255, 0, 0, 255, 255, 0, 0, 255, 255, 0, 0, 255, 255, 0, 0, 255});
  const std::vector<TextureLevel> levels = textureMipLevels(t);
  REQUIRE(levels.size() == 2);
  CHECK(levels[0].width == 2);
  CHECK(levels[0].height == 1);
  CHECK(levels[1].width == 1);
  CHECK(levels[1].height == 1);
  // Texel 0 of level 1: black, white, red, red -> linear red (0 + 1 + 1 + 1) / 4 = 0.75, green and
  // blue 0.25; sRGB bytes 225 and 137 (a plain byte average would give 191 and 64). Alpha: 255.
  const uint8_t* p = levels[0].rgba.data();
  CHECK(int(p[0]) == 225);
  CHECK(int(p[1]) == 137);
  CHECK(int(p[2]) == 137);
  CHECK(int(p[3]) == 255);
  // Texel 1: the white texel's alpha is 0: (255 + 0 + 255 + 255) / 4 = 191.25 -> 191.
  CHECK(int(p[7]) == 191);
  // Level 2 averages level 1's two texels, both alike but for alpha.
  CHECK(std::abs(int(levels[1].rgba[0]) - 225) <= 1);
  CHECK(int(levels[1].rgba[3]) == 223);
  // Odd sizes: 5 x 3 -> 2 x 1 -> 1 x 1; a 1 x 1 texture and an invalid one have no levels below.
  TextureImage odd;
  odd.width = 5;
  odd.height = 3;
  odd.rgba = std::make_shared<std::vector<uint8_t>>(5 * 3 * 4, uint8_t(90));
  const auto oddLevels = textureMipLevels(odd);
  REQUIRE(oddLevels.size() == 2);
  CHECK(oddLevels[0].width == 2);
  CHECK(oddLevels[0].height == 1);
  CHECK(int(oddLevels[1].rgba[0]) == 90);  // a flat image stays flat through the sRGB round trip
  odd.width = odd.height = 1;
  odd.rgba = std::make_shared<std::vector<uint8_t>>(4, uint8_t(7));
  CHECK(textureMipLevels(odd).empty());
  CHECK(textureMipLevels(TextureImage{}).empty());
}

TEST_CASE("textures: a mesh of two materials exports as two primitives and imports back with its parts and colours",
          "[textures][export]") {
  TempDir tmp;
  TexturedQuadOptions o;
  o.secondPrimitive = true;
  auto c = importGltf(test::writeTexturedQuad(tmp.path().string(), o));
  INFO((c ? std::string() : c.error()));
  REQUIRE(c);
  REQUIRE(c->meshes.at(0).parts.size() == 2);
  const std::string out = tmp.file("two_materials.glb");
  Status st = exportGlb(*c, out);
  INFO(st.error());
  REQUIRE(st.ok());
  auto back = importGltf(out);
  INFO((back ? std::string() : back.error()));
  REQUIRE(back);
  const Mesh& a = c->meshes[0];
  const Mesh& b = back->meshes.at(0);
  // The shared vertices are written once per primitive's attributes and concatenated again on
  // import: each part's triangles keep their corners' positions and their material.
  REQUIRE(b.parts.size() == 2);
  REQUIRE(back->materials.size() == c->materials.size());
  for (size_t k = 0; k < 2; ++k) {
    CAPTURE(k);
    CHECK(b.parts[k].indexCount == a.parts[k].indexCount);
    CHECK(b.parts[k].material == a.parts[k].material);
    for (uint32_t i = 0; i < a.parts[k].indexCount; ++i)
      CHECK(b.positions[b.indices[b.parts[k].firstIndex + i]] == a.positions[a.indices[a.parts[k].firstIndex + i]]);
  }
  CHECK(back->materials[1].baseColorFactor == c->materials[1].baseColorFactor);
  REQUIRE(back->textures.size() == c->textures.size());
  CHECK(back->materials[0].baseColorTexture == c->materials[0].baseColorTexture);
}

TEST_CASE("textures: a texture that cannot be decoded is named with its path and reason, the factor is kept",
          "[textures]") {
  TempDir tmp;
  TexturedQuadOptions o;
  o.image = TexturedQuadOptions::Image::CorruptFile;
  o.factor = {0.2f, 0.4f, 0.6f, 1.0f};
  auto c = importGltf(test::writeTexturedQuad(tmp.path().string(), o));
  INFO((c ? std::string() : c.error()));
  REQUIRE(c);  // the character still opens
  CHECK(c->textures.empty());
  CHECK(c->materials.at(0).baseColorTexture == -1);
  CHECK(c->materials.at(0).baseColorFactor == glm::vec4(0.2f, 0.4f, 0.6f, 1.0f));
  CHECK(anyWarningHas(*c, "quad.png: cannot decode: ", "drawn in its factor colour"));
  INFO(c->report.warnings.size());
}

TEST_CASE("textures: textured models of assimp-testmodels import with their textures decoded", "[textures][assimp]") {
  const std::string duck = "/usr/share/assimp/models/Collada/duck.dae";
  const std::string spider = "/usr/share/assimp/models/OBJ/spider.obj";
  if (!std::filesystem::exists(duck) || !std::filesystem::exists(spider))
    ANIMORPH_SKIP("assimp-testmodels is not installed (" + duck + ")");
  auto d = importAssimp(duck);
  REQUIRE(d);
  REQUIRE(d->textures.size() == 1);
  CHECK(d->textures[0].name == "duckCM.tga");
  CHECK(d->textures[0].width == 512);
  int textured = 0;
  for (const Material& m : d->materials) textured += m.baseColorTexture == 0;
  CHECK(textured >= 1);
  bool uv = false;
  for (const Mesh& m : d->meshes) uv |= m.texcoords0.size() == m.vertexCount() && m.vertexCount() > 0;
  CHECK(uv);
  auto s = importAssimp(spider);
  REQUIRE(s);
  CHECK(!s->textures.empty());
  for (const TextureImage& t : s->textures) CHECK(t.valid());
}

TEST_CASE("textures: a weight map from a texture's alpha equals a hand-sampled reference", "[textures][weights]") {
  TempDir tmp;
  TexturedQuadOptions o;
  auto c = importGltf(test::writeTexturedQuad(tmp.path().string(), o));
  INFO((c ? std::string() : c.error()));
  REQUIRE(c);
  // Nearest, clamped: the corners uv (0,0), (1,0), (1,1), (0,1) fall in texels (0,0), (1,0), (1,1), (0,1).
  auto a = weightMapFromTexture(*c, TextureChannel::Alpha);
  REQUIRE(a);
  const std::vector<float> nearest = {1.0f, 170 / 255.0f, 0.0f, 85 / 255.0f};
  REQUIRE(a->size() == 4);
  for (size_t v = 0; v < 4; ++v) CHECK((*a)[v] == Approx(nearest[v]).margin(1e-6));
  auto g = weightMapFromTexture(*c, TextureChannel::Green);
  REQUIRE(g);
  CHECK((*g)[1] == Approx(1.0f));  // the green texel
  CHECK((*g)[0] == Approx(0.0f));
  // Linear filter and KHR_texture_transform (u' = 0.5 + 0.5 u): vertex 0 at u' = 0.5 lies
  // between the centres of texels 0 and 1 of the top row, vertex 3 of the bottom row.
  TempDir tmp2;
  o.nearest = false;
  o.textureTransform = true;
  auto c2 = importGltf(test::writeTexturedQuad(tmp2.path().string(), o));
  REQUIRE(c2);
  auto b = weightMapFromTexture(*c2, TextureChannel::Alpha);
  REQUIRE(b);
  const std::vector<float> linear = {(255 + 170) / 2.0f / 255.0f, 170 / 255.0f, 0.0f, (85 + 0) / 2.0f / 255.0f};
  for (size_t v = 0; v < 4; ++v) CHECK((*b)[v] == Approx(linear[v]).margin(1e-6));
  // No texture: a clear error naming the file.
  Character plain = *c;
  plain.textures.clear();
  plain.materials[0].baseColorTexture = -1;
  plain.sourcePath = "plain.gltf";
  auto none = weightMapFromTexture(plain, TextureChannel::Alpha);
  REQUIRE_FALSE(none);
  CHECK(none.error().find("plain.gltf: no mesh has texture coordinates and a decoded base colour texture") == 0);
  CHECK(parseTextureChannel("alpha") == TextureChannel::Alpha);
  CHECK(parseTextureChannel("b") == TextureChannel::Blue);
  CHECK_FALSE(parseTextureChannel("luminance"));
}
