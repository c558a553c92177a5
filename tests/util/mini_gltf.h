#pragma once
// Small hand-written glTF files for importer tests: a JSON document plus one
// binary buffer assembled from typed arrays.
#include <cstdint>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

namespace animorph::test {

class MiniGltf {
 public:
  MiniGltf();
  // Appends values as a bufferView + accessor; returns the accessor index.
  int addFloats(const std::vector<float>& values, const char* type);
  int addU16(const std::vector<uint16_t>& values, const char* type);
  int addU8(const std::vector<uint8_t>& values, const char* type);
  // Appends raw bytes (an encoded image) as a bufferView; returns the bufferView index.
  int addBytes(const std::vector<uint8_t>& bytes);
  // One triangle mesh (POSITION, optional indices) with extra attributes; returns the mesh index.
  int addMesh(int positionAccessor, int indexAccessor, const nlohmann::json& extraAttributes = nlohmann::json::object());
  nlohmann::json& json() { return root_; }
  // Writes name (a .gltf) into dir with the buffer as "<bufferUri>" (an external
  // file written beside it) or embedded as a data: URI when bufferUri is empty.
  std::string write(const std::string& dir, const std::string& name, const std::string& bufferUri = "") const;

 private:
  int addView(const void* data, size_t bytes, int componentType, size_t count, const char* type);
  nlohmann::json root_;
  std::vector<uint8_t> bin_;
};

}  // namespace animorph::test
