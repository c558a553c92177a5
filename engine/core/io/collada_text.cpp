#include "core/io/collada_text.h"

#include <charconv>
#include <cmath>
#include <system_error>

namespace animorph::collada {

bool isSpace(char ch) { return ch == ' ' || ch == '\t' || ch == '\n' || ch == '\r'; }

size_t findIn(View b, View what, size_t from, size_t to) {
  if (from >= to || to > b.size()) return npos;
  const size_t p = b.substr(from, to - from).find(what);
  return p == npos ? npos : from + p;
}

Element findElement(View b, const std::string& name, size_t from, size_t to) {
  const std::string open = "<" + name;
  for (size_t p = findIn(b, open, from, to); p != npos; p = findIn(b, open, p + 1, to)) {
    const size_t after = p + open.size();
    if (after >= to || !(isSpace(b[after]) || b[after] == '>' || b[after] == '/')) continue;
    const size_t gt = findIn(b, ">", after, to);
    if (gt == npos) return {};
    Element e;
    e.at = p;
    e.begin = gt + 1;
    if (b[gt - 1] == '/') {
      e.close = e.end = gt + 1;
      return e;
    }
    e.close = findIn(b, "</" + name, e.begin, to);
    const size_t end = e.close == npos ? npos : findIn(b, ">", e.close, to);
    if (end == npos) return {};
    e.end = end + 1;
    return e;
  }
  return {};
}

std::string attribute(View b, const Element& e, View name) {
  const View tag = b.substr(e.at, e.begin - e.at);
  for (size_t p = tag.find(name); p != npos; p = tag.find(name, p + 1)) {
    if (p == 0 || !isSpace(tag[p - 1])) continue;
    size_t q = p + name.size();
    while (q < tag.size() && isSpace(tag[q])) ++q;
    if (q >= tag.size() || tag[q] != '=') continue;
    ++q;
    while (q < tag.size() && isSpace(tag[q])) ++q;
    if (q >= tag.size() || (tag[q] != '"' && tag[q] != '\'')) continue;
    const size_t end = tag.find(tag[q], q + 1);
    if (end == npos) return {};
    return std::string(tag.substr(q + 1, end - q - 1));
  }
  return {};
}

Element findById(View b, const std::string& name, const std::string& id, size_t from, size_t to) {
  for (Element e = findElement(b, name, from, to); e.at != npos; e = findElement(b, name, e.end, to))
    if (attribute(b, e, "id") == id) return e;
  return {};
}

std::vector<std::string> tokens(View b, const Element& e) {
  std::vector<std::string> out;
  size_t p = e.begin;
  while (p < e.close) {
    while (p < e.close && isSpace(b[p])) ++p;
    const size_t s = p;
    while (p < e.close && !isSpace(b[p])) ++p;
    if (p > s) out.emplace_back(b.substr(s, p - s));
  }
  return out;
}

Result<std::vector<float>> floats(const std::string& where, View b, const Element& e) {
  std::vector<float> out;
  const char* p = b.data() + e.begin;
  const char* end = b.data() + e.close;
  while (true) {
    while (p < end && isSpace(*p)) ++p;
    if (p >= end) return out;
    float v = 0.0f;
    const auto r = std::from_chars(p, end, v);
    if (r.ec != std::errc() || !std::isfinite(v))
      return Error{where + ": not a finite number at byte " + std::to_string(p - b.data())};
    out.push_back(v);
    p = r.ptr;
  }
}

}  // namespace animorph::collada
