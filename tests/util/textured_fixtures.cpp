#include "util/textured_fixtures.h"

#include <stb/stb_image_write.h>

#include <filesystem>
#include <fstream>

#include "util/mini_gltf.h"

namespace animorph::test {

namespace {

void appendBytes(void* context, void* data, int size) {
  auto* out = static_cast<std::vector<uint8_t>*>(context);
  const auto* p = static_cast<const uint8_t*>(data);
  out->insert(out->end(), p, p + size);
}

void writeBytes(const std::string& path, const std::vector<uint8_t>& bytes) {
  std::ofstream(path, std::ios::binary).write(reinterpret_cast<const char*>(bytes.data()), std::streamsize(bytes.size()));
}

}  // namespace

std::vector<uint8_t> encodePng(int width, int height, const std::vector<uint8_t>& rgba) {
  std::vector<uint8_t> out;
  if (!stbi_write_png_to_func(appendBytes, &out, width, height, 4, rgba.data(), width * 4)) out.clear();
  return out;
}

std::vector<uint8_t> encodeJpeg(int width, int height, const std::vector<uint8_t>& rgba) {
  std::vector<uint8_t> out;
  if (!stbi_write_jpg_to_func(appendBytes, &out, width, height, 4, rgba.data(), 95)) out.clear();
  return out;
}

std::vector<uint8_t> quadTexelBytes() {
  std::vector<uint8_t> px;
  for (const auto& t : kQuadTexels) px.insert(px.end(), t.begin(), t.end());
  return px;
}

std::string writeTexturedQuad(const std::string& dir, const TexturedQuadOptions& o) {
  using Image = TexturedQuadOptions::Image;
  MiniGltf g;
  std::vector<float> pos = {-1, 1, 0, 1, 1, 0, 1, -1, 0, -1, -1, 0};
  std::vector<float> nrm = {0, 0, 1, 0, 0, 1, 0, 0, 1, 0, 0, 1};
  std::vector<float> uv = {0, 0, 1, 0, 1, 1, 0, 1};
  const int p = g.addFloats(pos, "VEC3"), n = g.addFloats(nrm, "VEC3"), t = g.addFloats(uv, "VEC2");
  const int idx = g.addU16({0, 2, 1, 0, 3, 2}, "SCALAR");
  auto& j = g.json();
  nlohmann::json prim;
  prim["attributes"] = {{"POSITION", p}, {"NORMAL", n}, {"TEXCOORD_0", t}};
  prim["indices"] = idx;
  prim["material"] = 0;
  nlohmann::json mesh;
  mesh["primitives"] = nlohmann::json::array({prim});
  if (o.secondPrimitive) {
    for (size_t i = 0; i < pos.size(); i += 3) pos[i] += 2.5f;
    nlohmann::json second;
    second["attributes"] = {{"POSITION", g.addFloats(pos, "VEC3")}, {"NORMAL", g.addFloats(nrm, "VEC3")}};
    second["indices"] = idx;
    second["material"] = 1;
    mesh["primitives"].push_back(second);
  }
  j["meshes"] = nlohmann::json::array({mesh});
  j["nodes"] = {{{"mesh", 0}, {"name", "quad"}}};
  j["scenes"] = {{{"nodes", {0}}}};
  j["scene"] = 0;
  nlohmann::json texInfo = {{"index", 0}};
  if (o.textureTransform) {
    texInfo["extensions"]["KHR_texture_transform"] = {{"offset", {0.5, 0.0}}, {"scale", {0.5, 1.0}}};
    j["extensionsUsed"] = {"KHR_texture_transform"};
  }
  const std::vector<double> f = {o.factor.r, o.factor.g, o.factor.b, o.factor.a};
  j["materials"] = {{{"name", "textured"}, {"pbrMetallicRoughness", {{"baseColorFactor", f}, {"baseColorTexture", texInfo}}}}};
  if (o.secondPrimitive)
    j["materials"].push_back({{"name", "blue"}, {"pbrMetallicRoughness", {{"baseColorFactor", {0.1, 0.2, 0.9, 1.0}}}}});
  const int filter = o.nearest ? 9728 : 9729;
  j["samplers"] = {{{"magFilter", filter}, {"minFilter", filter}, {"wrapS", 33071}, {"wrapT", 33071}}};
  j["textures"] = {{{"source", 0}, {"sampler", 0}}};
  const std::vector<uint8_t> px = quadTexelBytes();
  const std::string base = std::filesystem::path(dir).string() + "/";
  switch (o.image) {
    case Image::PngFile: writeBytes(base + "quad.png", encodePng(2, 2, px)); j["images"] = {{{"uri", "quad.png"}}}; break;
    case Image::JpegFile: writeBytes(base + "quad.jpg", encodeJpeg(2, 2, px)); j["images"] = {{{"uri", "quad.jpg"}}}; break;
    case Image::CorruptFile:
      writeBytes(base + "quad.png", {0x89, 'P', 'N', 'G', 0x0d, 0x0a, 0x1a, 0x0a, 0, 0, 0, 13, 'I', 'H', 'D', 'R', 1, 2, 3});
      j["images"] = {{{"uri", "quad.png"}}};
      break;
    case Image::Missing: j["images"] = {{{"uri", "missing.png"}}}; break;
    case Image::Embedded:
      j["images"] = {{{"bufferView", g.addBytes(encodePng(2, 2, px))}, {"mimeType", "image/png"}}};
      break;
  }
  return g.write(dir, "quad.gltf");  // the buffer as a data: URI
}

}  // namespace animorph::test
