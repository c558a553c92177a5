#include "core/util/base64.h"

#include <cmath>
#include <cstdint>
#include <cstring>

namespace animorph {

namespace {

constexpr char kAlphabet[] = "ABCDEFGHIJKLMNOPQRSTUVWXYZabcdefghijklmnopqrstuvwxyz0123456789+/";

int decodeChar(char c) {
  if (c >= 'A' && c <= 'Z') return c - 'A';
  if (c >= 'a' && c <= 'z') return c - 'a' + 26;
  if (c >= '0' && c <= '9') return c - '0' + 52;
  if (c == '+') return 62;
  if (c == '/') return 63;
  return -1;
}

}  // namespace

std::string floatsToBase64(const std::vector<float>& values) {
  std::vector<uint8_t> bytes(values.size() * 4);
  for (size_t i = 0; i < values.size(); ++i) {
    uint32_t u;
    std::memcpy(&u, &values[i], 4);
    for (int k = 0; k < 4; ++k) bytes[i * 4 + size_t(k)] = uint8_t(u >> (8 * k));
  }
  std::string out;
  out.reserve((bytes.size() + 2) / 3 * 4);
  for (size_t i = 0; i < bytes.size(); i += 3) {
    const uint32_t b0 = bytes[i], b1 = i + 1 < bytes.size() ? bytes[i + 1] : 0, b2 = i + 2 < bytes.size() ? bytes[i + 2] : 0;
    const uint32_t v = (b0 << 16) | (b1 << 8) | b2;
    out += kAlphabet[(v >> 18) & 63];
    out += kAlphabet[(v >> 12) & 63];
    out += i + 1 < bytes.size() ? kAlphabet[(v >> 6) & 63] : '=';
    out += i + 2 < bytes.size() ? kAlphabet[v & 63] : '=';
  }
  return out;
}

Result<std::vector<float>> floatsFromBase64(const std::string& text, const std::string& where) {
  if (text.size() % 4 != 0) return Error{where + ": base64 length " + std::to_string(text.size()) + " is not a multiple of 4"};
  std::vector<uint8_t> bytes;
  bytes.reserve(text.size() / 4 * 3);
  for (size_t i = 0; i < text.size(); i += 4) {
    int v[4];
    int pad = 0;
    for (int k = 0; k < 4; ++k) {
      const char c = text[i + size_t(k)];
      if (c == '=' && i + 4 == text.size() && k >= 2) { v[k] = 0; ++pad; continue; }
      if (pad) return Error{where + ": bad base64 padding"};
      v[k] = decodeChar(c);
      if (v[k] < 0) return Error{where + ": invalid base64 character at offset " + std::to_string(i + size_t(k))};
    }
    const uint32_t w = (uint32_t(v[0]) << 18) | (uint32_t(v[1]) << 12) | (uint32_t(v[2]) << 6) | uint32_t(v[3]);
    bytes.push_back(uint8_t(w >> 16));
    if (pad < 2) bytes.push_back(uint8_t(w >> 8));
    if (pad < 1) bytes.push_back(uint8_t(w));
  }
  if (bytes.size() % 4 != 0) return Error{where + ": " + std::to_string(bytes.size()) + " bytes is not a whole number of float32 values"};
  std::vector<float> out(bytes.size() / 4);
  for (size_t i = 0; i < out.size(); ++i) {
    uint32_t u = 0;
    for (int k = 0; k < 4; ++k) u |= uint32_t(bytes[i * 4 + size_t(k)]) << (8 * k);
    std::memcpy(&out[i], &u, 4);
    if (!std::isfinite(out[i])) return Error{where + ": value " + std::to_string(i) + " is not finite"};
  }
  return out;
}

}  // namespace animorph
