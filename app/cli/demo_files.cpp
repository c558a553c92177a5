#include "app/cli/demo_files.h"

#include <cstdio>
#include <cstdlib>
#include <fstream>

#include "app/cli/cli_command.h"

namespace animorph::cli {

void shortenFloats(nlohmann::json& j) {
  if (j.is_number_float()) {
    double d = j.get<double>();
    float f = float(d);
    if (double(f) != d) return;  // a double (a key time), kept as it is
    char text[32];
    for (int digits = 1; digits <= 9; ++digits) {
      std::snprintf(text, sizeof text, "%.*g", digits, double(f));
      if (std::strtof(text, nullptr) == f) break;
    }
    j = std::strtod(text, nullptr);
  } else if (j.is_structured()) {
    for (auto& v : j) shortenFloats(v);
  }
}

Status writeCompact(nlohmann::json j, const std::filesystem::path& path) {
  shortenFloats(j);
  std::ofstream out(path, std::ios::binary | std::ios::trunc);
  out << j.dump() << "\n";
  out.close();
  if (!out) return Error{path.string() + ": cannot write"};
  return {};
}

bool outputDirectory(const char* command, const std::vector<std::string>& dirs, std::filesystem::path& dir) {
  if (dirs.size() != 1) {
    fail(command, "expected one argument: the output directory", 2);
    return false;
  }
  dir = dirs[0];
  std::error_code ec;
  std::filesystem::create_directories(dir, ec);
  if (ec) {
    fail(command, dir.string() + ": cannot create directory: " + ec.message());
    return false;
  }
  return true;
}

}  // namespace animorph::cli
