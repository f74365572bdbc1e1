#include "engine/lod/plumb_storage.h"

#include <fcntl.h>
#include <sys/stat.h>
#include <unistd.h>

#include <algorithm>
#include <cerrno>
#include <cmath>
#include <cstring>
#include <span>
#include <utility>

#include "engine/core/error.h"

namespace plumb::lod {
namespace {

void readAt(int fd, const std::string& path, std::uint64_t offset, std::span<std::byte> out) {
  std::size_t done = 0;
  while (done < out.size()) {
    const ssize_t got = ::pread(fd, out.data() + done, out.size() - done, static_cast<off_t>(offset + done));
    if (got < 0 && errno == EINTR) continue;
    if (got < 0) throw fileErrorAt(path, offset + done, "read failed (" + systemErrorText(errno) + ")");
    if (got == 0) throw fileErrorAt(path, offset + done, "truncated: the file ends early");
    done += static_cast<std::size_t>(got);
  }
}

class PlumbStorage final : public OctreeStorage {
 public:
  explicit PlumbStorage(std::string path) : path_(std::move(path)) {
    fd_ = ::open(path_.c_str(), O_RDONLY | O_CLOEXEC);
    if (fd_ < 0) throw fileError(path_, "cannot open (" + systemErrorText(errno) + ")");
  }
  ~PlumbStorage() override { ::close(fd_); }
  PlumbStorage(const PlumbStorage&) = delete;
  PlumbStorage& operator=(const PlumbStorage&) = delete;

  int fd() const { return fd_; }
  // The header is known once it has been read, through this storage's descriptor.
  void setHeader(const OctreeHeader& header) {
    cube_ = header.cube;
    attributes_ = header.attributes;
    version_ = header.version;
    scan_count_ = header.scan_count;
  }

  NodePoints load(const NodeInfo& node) const override {
    std::vector<std::byte> block(nodeBlockBytes(node.point_count, attributes_));
    readAt(fd_, path_, node.offset, block);
    if (crc32Of(block) != node.crc) {
      throw fileErrorAt(path_, node.offset,
                        "node (level " + std::to_string(node.key.level) + ", " + std::to_string(node.key.x) + ", " +
                            std::to_string(node.key.y) + ", " + std::to_string(node.key.z) +
                            ") is corrupt (checksum mismatch); rebuild the octree with 'plumb import'");
    }
    NodePoints result{node.key, cube_.cellMin(node.key), {}, {}};
    result.points.resize(node.point_count);
    for (std::size_t i = 0; i < node.point_count; ++i) result.points[i] = decodePoint(block.data() + i * kPointBytes);
    if (attributes_ & kHasScanIndex) {
      result.scans.resize(node.point_count);
      std::memcpy(result.scans.data(), block.data() + std::size_t{node.point_count} * kPointBytes,
                  result.scans.size() * sizeof(std::uint16_t));
      // The checksum holds, so only a writer's bug gets here: say so rather than index past the names.
      for (const std::uint16_t scan : result.scans) {
        if (scan >= scan_count_) {
          throw fileErrorAt(path_, node.offset,
                            "a point of node (level " + std::to_string(node.key.level) + ") names scan " +
                                std::to_string(scan) + " of " + std::to_string(scan_count_));
        }
      }
    }
    return result;
  }

  std::string format() const override { return "Plumb octree " + std::to_string(version_); }

 private:
  std::string path_;
  int fd_ = -1;
  Cube cube_;
  std::uint32_t attributes_ = 0;
  std::uint32_t version_ = kOctreeVersion;
  std::uint32_t scan_count_ = 0;
};

}  // namespace

OpenedOctree openPlumbOctree(const std::string& path) {
  auto storage = std::make_unique<PlumbStorage>(path);
  const int fd = storage->fd();
  struct stat status {};
  if (::fstat(fd, &status) != 0 || !S_ISREG(status.st_mode)) throw fileError(path, "is not a regular file");
  const auto file_size = static_cast<std::uint64_t>(status.st_size);
  // The magic first: a short file that is not an octree should say so, not "truncated".
  std::array<std::byte, kHeaderBytes> header_bytes{};
  readAt(fd, path, 0, std::span(header_bytes).first(std::min<std::uint64_t>(file_size, kHeaderBytes)));
  if (file_size < kOctreeMagic.size() ||
      std::memcmp(header_bytes.data(), kOctreeMagic.data(), kOctreeMagic.size()) != 0) {
    throw fileErrorAt(path, 0, "not a Plumb octree or a COPC file (build an octree with 'plumb import')");
  }
  if (file_size < kHeaderBytes) throw fileErrorAt(path, file_size, "truncated: shorter than an octree header");
  OpenedOctree opened;
  OctreeHeader& h = opened.header = decodeHeader(header_bytes, path);

  // Divide rather than multiply: node_count * kIndexEntryBytes can wrap to index_bytes (a node
  // count near 2^62 then passed this check and asked for an exabyte index).
  if (h.index_bytes % kIndexEntryBytes != 0 || h.index_bytes / kIndexEntryBytes != h.node_count ||
      h.index_offset < kHeaderBytes || h.index_offset > file_size || h.index_bytes > file_size - h.index_offset) {
    throw fileErrorAt(path, h.index_offset, "truncated or corrupt: the node index lies outside the file");
  }
  if (!(h.cube.size > 0.0) || !std::isfinite(h.cube.size) || !(h.root_spacing > 0.0)) {
    throw fileErrorAt(path, 32, "corrupt header: bad cube or spacing");
  }
  std::vector<std::byte> index(h.index_bytes);
  readAt(fd, path, h.index_offset, index);
  if (crc32Of(index) != h.index_crc) {
    throw fileErrorAt(path, h.index_offset, "the node index is corrupt (checksum mismatch); rebuild the octree");
  }
  opened.nodes.reserve(h.node_count);
  std::uint64_t points = 0;
  for (std::uint64_t i = 0; i < h.node_count; ++i) {
    const NodeInfo node = decodeIndexEntry(index.data() + i * kIndexEntryBytes, h.attributes);
    if (!node.key.valid() || node.offset < kHeaderBytes || node.offset > h.index_offset ||
        node.bytes > h.index_offset - node.offset) {
      throw fileErrorAt(path, h.index_offset + i * kIndexEntryBytes, "corrupt node index entry");
    }
    points += node.point_count;
    opened.nodes.push_back(node);
  }
  if (points != h.point_count) {
    throw fileErrorAt(
        path, h.index_offset,
        "the node index holds " + std::to_string(points) + " points, the header says " + std::to_string(h.point_count));
  }
  if (h.scan_count > 0) {
    if (h.scan_table_offset < kHeaderBytes || h.scan_table_offset > file_size ||
        h.scan_table_bytes > file_size - h.scan_table_offset) {
      throw fileErrorAt(path, h.scan_table_offset, "truncated or corrupt: the scan table lies outside the file");
    }
    std::vector<std::byte> table(h.scan_table_bytes);
    readAt(fd, path, h.scan_table_offset, table);
    if (crc32Of(table) != h.scan_table_crc) {
      throw fileErrorAt(path, h.scan_table_offset, "the scan table is corrupt (checksum mismatch); rebuild the octree");
    }
    h.scans = decodeScanTable(table, h.scan_count, path, h.scan_table_offset);
  }
  storage->setHeader(h);
  opened.storage = std::move(storage);
  return opened;
}

}  // namespace plumb::lod
