#include "engine/io/point_reader.h"

#include <algorithm>
#include <filesystem>
#include <fstream>

#include "engine/core/error.h"

namespace plumb::io {
namespace {

bool startsWith(const std::string& text, std::string_view prefix) {
  return text.rfind(prefix, 0) == 0;
}

}  // namespace

std::string lowerExtension(const std::string& path) {
  std::string extension = std::filesystem::path(path).extension().string();
  std::transform(extension.begin(), extension.end(), extension.begin(),
                 [](unsigned char c) { return static_cast<char>(std::tolower(c)); });
  return extension;
}

std::unique_ptr<PointReader> openPointCloud(const std::string& path, const ReaderOptions& options) {
  const std::string extension = lowerExtension(path);
  std::error_code error;
  if (!std::filesystem::exists(path, error)) throw fileError(path, "no such file");

  // The content decides where it can: extensions lie more often than magic numbers.
  std::string head(64, '\0');
  {
    std::ifstream in(path, std::ios::binary);
    if (!in) throw fileError(path, "cannot open for reading");
    in.read(head.data(), static_cast<std::streamsize>(head.size()));
    head.resize(static_cast<std::size_t>(in.gcount()));
  }
  if (startsWith(head, "ply\n") || startsWith(head, "ply\r\n")) return openPly(path);
  if (startsWith(head, "LASF")) return openLas(path);  // LAS and LAZ
  if (startsWith(head, "ASTM-E57")) return openE57(path);
  if (startsWith(head, "# .PCD") || startsWith(head, "VERSION") || startsWith(head, "FIELDS") || extension == ".pcd") {
    return openPcd(path);
  }
  for (const char* ascii : {".xyz", ".txt", ".pts", ".csv", ".asc"}) {
    if (extension == ascii) return openAscii(path, options);
  }
  if (extension == ".las" || extension == ".laz") {
    throw fileError(path,
                    "not a LAS or LAZ file: it does not start with \"LASF\" (a damaged file, or another "
                    "format under this extension)");
  }
  throw fileError(
      path, "unknown point-cloud format; Plumb reads PLY, LAS, LAZ, PCD, E57 and ASCII (.xyz .txt .pts .csv .asc)");
}

}  // namespace plumb::io
