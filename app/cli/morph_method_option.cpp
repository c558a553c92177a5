#include "app/cli/morph_method_option.h"

namespace animorph::cli {

bool readMorphMethodOption(const std::vector<std::string>& args, size_t& i, MorphMethodOptions& out,
                           std::string& error) {
  const std::string& a = args[i];
  const bool blend = a == "--correspondence-blend";
  if (a != "--method" && !blend) return false;
  if (i + 1 >= args.size()) {
    error = a + " needs a value";
    return true;
  }
  const std::string& v = args[++i];
  MorphMethod m{};
  if (!morphMethodFromName(v, m) || (blend && m == MorphMethod::SkeletonCorrespondence)) {
    error = a + ": expected " +
            (blend ? "interpolation or space_time" : "interpolation, space_time or skeleton_correspondence") +
            ", got '" + v + "'";
    return true;
  }
  (blend ? out.correspondenceBlend : out.method) = m;
  return true;
}

void applyMorphMethodOptions(const MorphMethodOptions& o, MorphSetup& m) {
  if (o.method) m.method = *o.method;
  if (o.correspondenceBlend) m.correspondenceBlend = *o.correspondenceBlend;
}

}  // namespace animorph::cli
