#pragma once
// Reading a Collada document's text directly, for the parts assimp 5.2 cannot read (io/collada_morphs,
// io/collada_morph_weights): elements found by name in a byte range, their attributes, and the
// numbers and names of their arrays. No XML tree is built: every search is linear in the range it
// is given, and the arrays are parsed from the document's own text (at most one value per two bytes).
#include <cstddef>
#include <string>
#include <string_view>
#include <vector>

#include "core/util/result.h"

namespace animorph::collada {

using View = std::string_view;
inline constexpr size_t npos = std::string::npos;

// ' ', '\t', '\n' or '\r'.
bool isSpace(char ch);

// The first byte of `what` in b[from, to), or npos (also when the range is empty or past b's end).
size_t findIn(View b, View what, size_t from, size_t to);

// An element: its start tag [at, begin), content [begin, close), the whole [at, end). at == npos: none.
struct Element {
  size_t at = npos, begin = 0, close = 0, end = 0;
};

// The first element `name` starting in [from, to). The first "</name" after the start tag closes
// it: correct for the elements that do not nest in Collada (not for <animation> or <node>).
Element findElement(View b, const std::string& name, size_t from, size_t to);

// The value of attribute `name` in e's start tag ("" when absent).
std::string attribute(View b, const Element& e, View name);

// The element `name` in [from, to) whose id is `id` (at == npos: none). Linear in the range.
Element findById(View b, const std::string& name, const std::string& id, size_t from, size_t to);

// The white-space separated words of e's content (an IDREF_array's or Name_array's names).
std::vector<std::string> tokens(View b, const Element& e);

// The numbers of e's content (a <float_array>); fails with `where` and the byte offset of the first
// word that is not a finite number.
Result<std::vector<float>> floats(const std::string& where, View b, const Element& e);

}  // namespace animorph::collada
