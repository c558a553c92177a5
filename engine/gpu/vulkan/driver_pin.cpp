#include "gpu/vulkan/driver_pin.h"

#if defined(__SANITIZE_ADDRESS__)  // GCC
#define ANIMORPH_ADDRESS_SANITIZER 1
#elif defined(__has_feature)  // clang
#if __has_feature(address_sanitizer)
#define ANIMORPH_ADDRESS_SANITIZER 1
#endif
#endif

#if defined(ANIMORPH_ADDRESS_SANITIZER)
#include <dlfcn.h>
#include <link.h>

#include <cstring>
#include <string>
#include <vector>
#endif

namespace animorph::gpu {

void keepVulkanDriversLoadedUnderSanitizer() {
#if defined(ANIMORPH_ADDRESS_SANITIZER)
  // The names are gathered first and opened after: dlopen is not called from inside
  // dl_iterate_phdr's callback, which runs under the loader's lock.
  std::vector<std::string> drivers;
  dl_iterate_phdr(
      [](dl_phdr_info* info, size_t, void* out) -> int {
        if (info->dlpi_name && std::strstr(info->dlpi_name, "libvulkan_"))
          static_cast<std::vector<std::string>*>(out)->push_back(info->dlpi_name);
        return 0;
      },
      &drivers);
  // RTLD_NOLOAD: only drivers already open; RTLD_NODELETE: never unloaded, even by the loader's dlclose.
  for (const std::string& d : drivers) dlopen(d.c_str(), RTLD_NOW | RTLD_NOLOAD | RTLD_NODELETE);
#endif
}

}  // namespace animorph::gpu
