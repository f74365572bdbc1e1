#pragma once
// Reading a released swapchain image back to the host in xrEndFrame, for the captured frames'
// PNGs (OpenXR 1.0 specification, chapter 12, section "XR_KHR_vulkan_enable2": a released image is
// in COLOR_ATTACHMENT_OPTIMAL and owned by the binding's queue, where the runtime must leave it).

#include <cstdint>
#include <vector>

#include "tests/support/xr_headset/vulkan_commands.h"

namespace plumb::xr_headset {

// Copies `rect` of mip level 0, array layer `array_layer` of `image` (a colour image in
// COLOR_ATTACHMENT_OPTIMAL, of a format isReadableColorFormat accepts) into `rgba`: 4 bytes a
// pixel, R first, rows top to bottom. The stored bytes as they are (no sRGB decoding); BGRA formats
// are swizzled. The image is back in COLOR_ATTACHMENT_OPTIMAL when this returns. Submits on the
// binding's queue and waits. False on failure (reported on stderr).
bool readColorImage(const VulkanBinding& binding, OneShotCommands& commands, VkImage image, VkFormat format,
                    std::uint32_t array_layer, const XrRect2Di& rect, std::vector<std::uint8_t>& rgba);

// The same for a depth image (in DEPTH_STENCIL_ATTACHMENT_OPTIMAL, D32_SFLOAT or D16_UNORM, left
// there): one float a pixel, the stored depth (D16 as a fraction of 65535).
bool readDepthImage(const VulkanBinding& binding, OneShotCommands& commands, VkImage image, VkFormat format,
                    std::uint32_t array_layer, const XrRect2Di& rect, std::vector<float>& depths);

}  // namespace plumb::xr_headset
