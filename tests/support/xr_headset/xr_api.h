#pragma once
// The OpenXR and Vulkan declarations every file of the simulated headset sees: Vulkan first, then
// OpenXR with its Vulkan platform types (OpenXR 1.0 specification, chapter 12, section
// "XR_KHR_vulkan_enable2"). The runtime defines XR_NO_PROTOTYPES (CMakeLists.txt): it implements the
// API, so calling the loader's exported functions from inside it would always be a mistake.

#include <vulkan/vulkan.h>

#ifndef XR_USE_GRAPHICS_API_VULKAN
#define XR_USE_GRAPHICS_API_VULKAN
#endif
#include <openxr/openxr.h>
#include <openxr/openxr_platform.h>
