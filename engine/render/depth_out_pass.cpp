#include "engine/render/depth_out_pass.h"

#include <cassert>

#include "engine/gpu/commands.h"
#include "engine/gpu/deletion_queue.h"
#include "engine/gpu/device.h"
#include "engine/gpu/image.h"
#include "engine/gpu/vk_check.h"
#include "engine/render/render_target.h"
#include "engine/view/camera.h"
#include "shaders/render_layout.h"

namespace plumb::render {
namespace {

constexpr std::uint32_t kVertexCode[] =
#include "shaders/depth_out.vert.inc"
    ;
constexpr std::uint32_t kFragmentCode[] =
#include "shaders/depth_out.frag.inc"
    ;

static_assert(sizeof(shader::DepthOutPush) == 24, "DepthOutPush differs from its std430 layout");

}  // namespace

DepthOutPass::DepthOutPass(const gpu::Device& device) : device_(device) {}

DepthOutPass::~DepthOutPass() = default;

void DepthOutPass::record(VkCommandBuffer commands, const RenderTarget& target, const view::Camera& camera,
                          VkImage image, VkFormat format, VkImageLayout final_layout, gpu::DeletionQueue& deletions,
                          std::uint64_t frame_value) {
  assert((format == VK_FORMAT_D32_SFLOAT || format == VK_FORMAT_D16_UNORM) && "a depth format without stencil");
  std::unique_ptr<gpu::GraphicsPipeline>& pipeline = pipelines_[format];
  if (!pipeline) {
    pipeline = std::make_unique<gpu::GraphicsPipeline>(
        device_, kVertexCode, kFragmentCode, sizeof(shader::DepthOutPush), VK_FORMAT_UNDEFINED, "depth out", format);
  }
  const VkImageView view =
      gpu::createImageView(device_.handle(), image, format, VK_IMAGE_ASPECT_DEPTH_BIT, "headset eye's depth");
  deletions.defer(frame_value, [device = device_.handle(), view] { vkDestroyImageView(device, view, nullptr); });

  // The resolve's writes before the fragment shader's reads; the image's old content goes.
  gpu::memoryBarrier(commands, VK_PIPELINE_STAGE_2_COMPUTE_SHADER_BIT, VK_ACCESS_2_SHADER_WRITE_BIT,
                     VK_PIPELINE_STAGE_2_FRAGMENT_SHADER_BIT, VK_ACCESS_2_SHADER_READ_BIT);
  const VkPipelineStageFlags2 depth_stages =
      VK_PIPELINE_STAGE_2_EARLY_FRAGMENT_TESTS_BIT | VK_PIPELINE_STAGE_2_LATE_FRAGMENT_TESTS_BIT;
  gpu::imageBarrier(commands, image, VK_IMAGE_LAYOUT_UNDEFINED, VK_IMAGE_LAYOUT_DEPTH_ATTACHMENT_OPTIMAL, depth_stages,
                    VK_ACCESS_2_NONE, depth_stages, VK_ACCESS_2_DEPTH_STENCIL_ATTACHMENT_WRITE_BIT,
                    VK_IMAGE_ASPECT_DEPTH_BIT);
  VkRenderingAttachmentInfo attachment{};
  attachment.sType = VK_STRUCTURE_TYPE_RENDERING_ATTACHMENT_INFO;
  attachment.imageView = view;
  attachment.imageLayout = VK_IMAGE_LAYOUT_DEPTH_ATTACHMENT_OPTIMAL;
  attachment.loadOp = VK_ATTACHMENT_LOAD_OP_DONT_CARE;
  attachment.storeOp = VK_ATTACHMENT_STORE_OP_STORE;
  VkRenderingInfo rendering{};
  rendering.sType = VK_STRUCTURE_TYPE_RENDERING_INFO;
  rendering.renderArea = {{0, 0}, {target.width, target.height}};
  rendering.layerCount = 1;
  rendering.pDepthAttachment = &attachment;
  vkCmdBeginRendering(commands, &rendering);
  const shader::DepthOutPush push{target.resolved.address(), target.width, static_cast<float>(camera.near_m),
                                  static_cast<float>(camera.far_m), 0u};
  pipeline->draw(commands, push, 3, target.width, target.height);
  vkCmdEndRendering(commands);
  gpu::imageBarrier(commands, image, VK_IMAGE_LAYOUT_DEPTH_ATTACHMENT_OPTIMAL, final_layout, depth_stages,
                    VK_ACCESS_2_DEPTH_STENCIL_ATTACHMENT_WRITE_BIT, VK_PIPELINE_STAGE_2_NONE, VK_ACCESS_2_NONE,
                    VK_IMAGE_ASPECT_DEPTH_BIT);
}

}  // namespace plumb::render
