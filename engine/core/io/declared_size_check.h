#pragma once
// What a FBX or Collada file says it will decode to, checked before a parser allocates it.
// assimp sizes its arrays from the counts a file declares (a binary FBX array's element count
// and zlib-compressed length, an ASCII FBX "*N {" or a Collada count="N"); a small file that
// declares huge arrays would make it allocate gigabytes. These checks read only the file's
// bytes and refuse such a file with the element and the sizes, in time linear in its size.
#include <cstddef>
#include <string>

#include "core/util/result.h"

namespace animorph {

// All arrays a file declares together may decode to at most kImportDecodeFactor times the
// file's size plus kImportDecodeAllowance bytes (the same idea as the glTF decoding budget,
// with room for FBX's zlib-compressed arrays, which real exporters compress 2-6 times).
inline constexpr size_t kImportDecodeFactor = 16;
inline constexpr size_t kImportDecodeAllowance = size_t(64) << 20;

// zlib cannot expand data by more than about 1032:1; a compressed FBX array that claims more
// is malformed.
inline constexpr size_t kZlibMaxExpansion = 1032;

// Binary FBX (bytes start with "Kaydara FBX Binary"): walks every node record and property;
// refuses records that leave their parent or the file, arrays whose stored length does not
// match their element count (uncompressed) or exceeds zlib's expansion (compressed), unknown
// property types or encodings, and a sum of decoded array sizes over the budget. Errors name
// file (the path as given), the record's byte offset and name, and the reason.
Status checkFbxBinaryDeclaredSizes(const std::string& file, const std::string& bytes);

// Text formats (ASCII FBX "*N {" arrays, Collada count="N" attributes): the sum of the
// declared counts, at 8 bytes an element, must fit the budget. Errors name file, the byte
// offset and the count.
Status checkTextDeclaredCounts(const std::string& file, const std::string& bytes, bool collada);

// Collada index lists (<p>, and <h> of a polygon with holes): only digits and white space.
// libassimp 5.2 reads such a list until its end, one unsigned integer at a time, and does not move
// past a character that starts none ("1.5", a stray byte): it appends zeros until memory runs out.
// Errors name file, the element, its byte offset and the character. Time linear in the size.
Status checkColladaIndexLists(const std::string& file, const std::string& bytes);

// Collada skin weights (<vertex_weights count="N">): its <vcount> lists N numbers, and its <v> lists
// their sum times the inputs' stride (the largest input offset + 1) indices. libassimp 5.2 trusts
// count and reads past the lists it sized by it (a null read in its skin conversion). Errors name
// file, the element, its byte offset and what disagrees. Time linear in the size.
Status checkColladaVertexWeights(const std::string& file, const std::string& bytes);

// Collada accessors (<accessor source="#array" count="C" stride="S" offset="O">): every child is a
// <param>, at most S of them, and the array named by source (found in the same file) holds at least
// O + C * S values. libassimp 5.2 trusts the accessor and asserts (aborting the process) when it
// reads past the array. Errors name file, the accessor, its byte offset and what disagrees.
Status checkColladaAccessors(const std::string& file, const std::string& bytes);

// True when bytes start with the binary FBX magic.
bool isFbxBinary(const std::string& bytes);

}  // namespace animorph
