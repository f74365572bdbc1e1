// frames.jsonl and the captured PNGs (frame_output.h). PNG encoding by stb_image_write, whose
// implementation is inside Debian's libstb.

#include "tests/support/xr_headset/frame_output.h"

#include <stb_image_write.h>

#include <cstdio>
#include <filesystem>
#include <fstream>
#include <nlohmann/json.hpp>
#include <system_error>

namespace plumb::xr_headset {
namespace {

std::string padded(std::uint64_t frame) {
  std::string digits = std::to_string(frame);
  if (digits.size() < 4) digits.insert(0, 4 - digits.size(), '0');
  return digits;
}

// "<first>-<kind>-<index>.<extension>", the first part a frame's ("frame-NNNN") or "latest".
// Appended: GCC 12 -O3 warns (-Wrestrict) on a literal + std::string.
std::string imageName(const std::string& first, const char* kind, std::uint32_t index, const char* extension) {
  std::string name = first;
  name += '-';
  name += kind;
  name += '-';
  name += std::to_string(index);
  name += '.';
  name += extension;
  return name;
}

std::string frameName(std::uint64_t frame) {
  std::string name = "frame-";
  name += padded(frame);
  return name;
}

}  // namespace

std::string frameJsonLine(const SubmittedFrame& frame) {
  nlohmann::json views = nlohmann::json::array();
  for (const SubmittedView& view : frame.views) {
    const Pose& pose = view.pose;
    views.push_back({
        {"pose",
         {{"position", {pose.position.x, pose.position.y, pose.position.z}},
          {"orientation", {pose.orientation.x, pose.orientation.y, pose.orientation.z, pose.orientation.w}}}},
        {"fov",
         {{"left", view.fov.angleLeft},
          {"right", view.fov.angleRight},
          {"up", view.fov.angleUp},
          {"down", view.fov.angleDown}}},
        {"image_rect",
         {view.image_rect.offset.x, view.image_rect.offset.y, view.image_rect.extent.width,
          view.image_rect.extent.height}},
        {"depth", view.depth},
    });
    if (view.depth) views.back()["depth_range"] = {view.near_z, view.far_z};
  }
  const nlohmann::json line{{"frame", frame.frame},
                            {"display_time", frame.display_time},
                            {"layers", frame.layer_count},
                            {"views", views},
                            {"quads", frame.quad_count}};
  return line.dump();
}

bool appendFrameLine(const std::string& folder, const std::string& line) {
  const std::filesystem::path path = std::filesystem::path(folder) / "frames.jsonl";
  std::ofstream out(path, std::ios::app | std::ios::binary);
  out << line << '\n';
  out.flush();
  if (!out) {
    std::fprintf(stderr, "simulated headset: cannot append to %s\n", path.c_str());
    return false;
  }
  return true;
}

std::string eyeImageName(std::uint64_t frame, std::uint32_t eye) {
  return imageName(frameName(frame), "eye", eye, "png");
}

std::string latestEyeImageName(std::uint32_t eye) {
  return imageName("latest", "eye", eye, "png");
}

std::string depthImageName(std::uint64_t frame, std::uint32_t eye) {
  return imageName(frameName(frame), "depth", eye, "pfm");
}

std::string latestDepthImageName(std::uint32_t eye) {
  return imageName("latest", "depth", eye, "pfm");
}

std::string quadImageName(std::uint64_t frame, std::uint32_t quad) {
  return imageName(frameName(frame), "quad", quad, "png");
}

namespace {

// Writes `bytes` to `folder`/`name` through a temporary file renamed into place, so that a reader
// never sees half a file.
bool writeFile(const std::string& folder, const std::string& name, const std::vector<char>& bytes) {
  const std::filesystem::path path = std::filesystem::path(folder) / name;
  const std::filesystem::path temporary = std::filesystem::path(folder) / ("." + name + ".partial");
  {
    std::ofstream out(temporary, std::ios::binary | std::ios::trunc);
    out.write(bytes.data(), static_cast<std::streamsize>(bytes.size()));
    out.flush();
    if (!out) {
      std::fprintf(stderr, "simulated headset: cannot write %s\n", temporary.c_str());
      return false;
    }
  }
  std::error_code error;
  std::filesystem::rename(temporary, path, error);
  if (error) {
    std::fprintf(stderr, "simulated headset: cannot rename %s to %s: %s\n", temporary.c_str(), path.c_str(),
                 error.message().c_str());
    return false;
  }
  return true;
}

}  // namespace

bool writePfm(const std::string& folder, const std::string& name, std::uint32_t width, std::uint32_t height,
              const std::vector<float>& depths) {
  const std::string header = "Pf\n" + std::to_string(width) + ' ' + std::to_string(height) + "\n-1.0\n";
  std::vector<char> bytes(header.begin(), header.end());  // a negative scale: little-endian floats
  for (std::uint32_t row = height; row-- > 0;) {          // bottom to top, as the format has them
    const auto* first = reinterpret_cast<const char*>(depths.data() + std::size_t{row} * width);
    bytes.insert(bytes.end(), first, first + std::size_t{width} * sizeof(float));
  }
  return writeFile(folder, name, bytes);
}

bool writePng(const std::string& folder, const std::string& name, std::uint32_t width, std::uint32_t height,
              const std::vector<std::uint8_t>& rgba) {
  std::vector<char> png;
  auto append = [](void* context, void* data, int size) {
    auto* out = static_cast<std::vector<char>*>(context);
    out->insert(out->end(), static_cast<const char*>(data), static_cast<const char*>(data) + size);
  };
  const int stride = static_cast<int>(width) * 4;
  if (stbi_write_png_to_func(append, &png, static_cast<int>(width), static_cast<int>(height), 4, rgba.data(), stride) ==
      0) {
    std::fprintf(stderr, "simulated headset: PNG encoding failed for %s/%s\n", folder.c_str(), name.c_str());
    return false;
  }
  return writeFile(folder, name, png);
}

}  // namespace plumb::xr_headset
