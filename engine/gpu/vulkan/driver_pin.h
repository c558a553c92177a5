#pragma once
// Keeps the Vulkan drivers (ICDs) that the loader has opened loaded until the process exits, in
// builds with AddressSanitizer only (./run.sh test --asan); elsewhere it does nothing.
//
// Why: the Vulkan loader dlcloses each driver at vkDestroyInstance. Mesa's lavapipe keeps a few
// small allocations referenced only from its own data; once the driver is unloaded, LeakSanitizer
// sees them as unreferenced at exit and reports a leak, and it can no longer name the unloaded
// module, so no suppression can match. A driver kept loaded keeps its data as a root: the report
// goes away without hiding any leak in Animorph's own code (whose allocations are never
// referenced from a driver's data).
namespace animorph::gpu {

// Call after the instance enumerated its physical devices (the drivers are loaded then).
// Idempotent; cheap.
void keepVulkanDriversLoadedUnderSanitizer();

}  // namespace animorph::gpu
