#include "engine/render/overlay_pass.h"

#include <algorithm>
#include <cstring>

#include "engine/gpu/commands.h"
#include "engine/render/overlay_scene.h"
#include "engine/render/overlay_vertices.h"
#include "engine/render/render_target.h"
#include "engine/view/camera.h"
#include "shaders/render_layout.h"

namespace plumb::render {
namespace {

constexpr std::uint32_t kVertexCode[] =
#include "shaders/overlay.vert.inc"
    ;
constexpr std::uint32_t kFragmentCode[] =
#include "shaders/overlay.frag.inc"
    ;

static_assert(sizeof(shader::OverlayVertex) == 40, "OverlayVertex differs from its std430 layout");
static_assert(sizeof(shader::OverlayPush) == 112, "OverlayPush differs from its std430 layout");

}  // namespace

OverlayPass::OverlayPass(const gpu::Device& device, gpu::MemoryAllocator& allocator)
    : device_(device),
      allocator_(allocator),
      pipeline_(device, kVertexCode, kFragmentCode, sizeof(shader::OverlayPush), RenderTarget::kColourFormat,
                "overlay") {}

bool OverlayPass::record(VkCommandBuffer commands, std::size_t slot, const RenderTarget& target,
                         const OverlayScene& scene, const view::Camera& camera, float depth_tolerance) {
  const std::vector<shader::OverlayVertex> vertices = overlayVertices(scene, camera.position);
  if (vertices.empty()) return false;
  const VkDeviceSize bytes = vertices.size() * sizeof(shader::OverlayVertex);
  gpu::Buffer& buffer = vertices_[slot];
  if (!buffer || buffer.size() < bytes) {
    // The slot's last frame is done: its buffer may go now.
    buffer = gpu::Buffer(device_, allocator_, std::max<VkDeviceSize>(bytes, 2 * buffer.size()),
                         VK_BUFFER_USAGE_STORAGE_BUFFER_BIT, gpu::kHostMemory, "overlay vertices");
  }
  std::memcpy(buffer.mapped(), vertices.data(), bytes);

  // Vulkan clip space (y down, depth 0..1) from positions relative to the eye.
  Eigen::Matrix4d view = view::viewMatrix(camera);
  view.block<3, 1>(0, 3).setZero();
  Eigen::Matrix4d vulkan_from_gl = Eigen::Matrix4d::Identity();
  vulkan_from_gl(1, 1) = -1.0;
  vulkan_from_gl(2, 2) = 0.5;
  vulkan_from_gl(2, 3) = 0.5;
  const Eigen::Matrix4f clip_from_eye = (vulkan_from_gl * view::projectionMatrix(camera) * view).cast<float>();
  const Eigen::Vector4f depth_from_eye = (-view.row(2)).transpose().cast<float>();
  shader::OverlayPush push{};
  push.vertices = buffer.address();
  push.resolved = target.resolved.address();
  std::memcpy(push.clip_from_eye, clip_from_eye.data(), sizeof push.clip_from_eye);
  std::memcpy(push.depth_from_eye, depth_from_eye.data(), sizeof push.depth_from_eye);
  push.width = target.width;
  push.height = target.height;
  push.depth_tolerance = depth_tolerance;

  const VkImage image = target.colour_image.handle();
  gpu::memoryBarrier(commands, VK_PIPELINE_STAGE_2_COMPUTE_SHADER_BIT, VK_ACCESS_2_SHADER_WRITE_BIT,
                     VK_PIPELINE_STAGE_2_FRAGMENT_SHADER_BIT, VK_ACCESS_2_SHADER_READ_BIT);  // the resolved depths
  target.copyColourToImage(commands, VK_IMAGE_LAYOUT_COLOR_ATTACHMENT_OPTIMAL,
                           VK_PIPELINE_STAGE_2_COLOR_ATTACHMENT_OUTPUT_BIT,
                           VK_ACCESS_2_COLOR_ATTACHMENT_READ_BIT | VK_ACCESS_2_COLOR_ATTACHMENT_WRITE_BIT);

  VkRenderingAttachmentInfo attachment{};
  attachment.sType = VK_STRUCTURE_TYPE_RENDERING_ATTACHMENT_INFO;
  attachment.imageView = target.colour_image.view();
  attachment.imageLayout = VK_IMAGE_LAYOUT_COLOR_ATTACHMENT_OPTIMAL;
  attachment.loadOp = VK_ATTACHMENT_LOAD_OP_LOAD;
  attachment.storeOp = VK_ATTACHMENT_STORE_OP_STORE;
  VkRenderingInfo rendering{};
  rendering.sType = VK_STRUCTURE_TYPE_RENDERING_INFO;
  rendering.renderArea = {{0, 0}, {target.width, target.height}};
  rendering.layerCount = 1;
  rendering.colorAttachmentCount = 1;
  rendering.pColorAttachments = &attachment;
  vkCmdBeginRendering(commands, &rendering);
  pipeline_.draw(commands, push, static_cast<std::uint32_t>(vertices.size()), target.width, target.height);
  vkCmdEndRendering(commands);

  gpu::imageBarrier(commands, image, VK_IMAGE_LAYOUT_COLOR_ATTACHMENT_OPTIMAL, VK_IMAGE_LAYOUT_TRANSFER_SRC_OPTIMAL,
                    VK_PIPELINE_STAGE_2_COLOR_ATTACHMENT_OUTPUT_BIT, VK_ACCESS_2_COLOR_ATTACHMENT_WRITE_BIT,
                    VK_PIPELINE_STAGE_2_COPY_BIT, VK_ACCESS_2_TRANSFER_READ_BIT);
  const VkBufferImageCopy region = target.colourRegion();
  vkCmdCopyImageToBuffer(commands, image, VK_IMAGE_LAYOUT_TRANSFER_SRC_OPTIMAL, target.colour.handle(), 1, &region);
  return true;
}

}  // namespace plumb::render
