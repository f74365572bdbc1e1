#include "engine/io/laszip_vlr.h"

#include <array>

#include "engine/io/byte_order.h"
#include "engine/io/laz_layered_items.h"

namespace plumb::io {
namespace {

// Payload offsets.
constexpr std::size_t kCompressorAt = 0;
constexpr std::size_t kCoderAt = 2;
constexpr std::size_t kVersionMajorAt = 4;
constexpr std::size_t kVersionMinorAt = 5;
constexpr std::size_t kVersionRevisionAt = 6;
constexpr std::size_t kChunkSizeAt = 12;
constexpr std::size_t kItemCountAt = 32;
constexpr std::size_t kItemsAt = 34;
constexpr std::size_t kItemBytes = 6;

constexpr std::uint16_t kArithmeticCoder = 0;

struct ItemRule {
  LazItemType type;
  std::uint16_t size;  // 0: any size from 1 (BYTE)
};

// The standard part of LAS point formats 0 to 3 as items (record sizes 20, 28, 26, 34).
constexpr std::array<std::uint16_t, 4> kStandardBytes{20, 28, 26, 34};

std::string itemList(const std::vector<LazItem>& items) {
  std::string text;
  for (const LazItem& item : items) {
    if (!text.empty()) text += ", ";
    text += lazItemName(item.type) + " (" + std::to_string(item.size) + " bytes)";
  }
  return text;
}

// The items point format `format` (0 to 3) with `record_length`-byte records is made of.
std::vector<LazItem> itemsOfFormat(unsigned format, std::size_t record_length) {
  std::vector<LazItem> items{{static_cast<std::uint16_t>(LazItemType::kPoint10), 20, 0}};
  if (format == 1 || format == 3) items.push_back({static_cast<std::uint16_t>(LazItemType::kGpsTime11), 8, 0});
  if (format == 2 || format == 3) items.push_back({static_cast<std::uint16_t>(LazItemType::kRgb12), 6, 0});
  if (record_length > kStandardBytes[format]) {
    items.push_back({static_cast<std::uint16_t>(LazItemType::kByte),
                     static_cast<std::uint16_t>(record_length - kStandardBytes[format]), 0});
  }
  return items;
}

// The layered coder's items of LAS 1.4 point formats 6 to 8: POINT14, RGB14 (7) or RGBNIR14 (8),
// then BYTE14 for the extra bytes.
std::vector<LazItem> itemsOfFormat14(unsigned format, std::size_t record_length) {
  constexpr std::array<std::size_t, 3> kBytes14{30, 36, 38};
  std::vector<LazItem> items{{static_cast<std::uint16_t>(LazItemType::kPoint14), 30, 0}};
  if (format == 7) items.push_back({static_cast<std::uint16_t>(LazItemType::kRgb14), 6, 0});
  if (format == 8) items.push_back({static_cast<std::uint16_t>(LazItemType::kRgbNir14), 8, 0});
  if (record_length > kBytes14[format - 6]) {
    items.push_back({static_cast<std::uint16_t>(LazItemType::kByte14),
                     static_cast<std::uint16_t>(record_length - kBytes14[format - 6]), 0});
  }
  return items;
}

// Checks the items of a layered (compressor 3) VLR, as readLaszipVlr documents.
void checkLayeredItems(const LaszipVlr& vlr, std::uint64_t at, const FileSource& source, unsigned format,
                       std::size_t record_length) {
  const std::string where = "the laszip VLR";
  for (std::size_t i = 0; i < vlr.items.size(); ++i) {
    const LazItem& item = vlr.items[i];
    const std::uint64_t item_at = at + kItemsAt + kItemBytes * i;
    const std::string name = "item " + std::to_string(i + 1) + " of " + where;
    switch (static_cast<LazItemType>(item.type)) {
      case LazItemType::kPoint14:
      case LazItemType::kRgb14:
      case LazItemType::kRgbNir14:
      case LazItemType::kByte14:
        break;
      case LazItemType::kWavePacket13:
      case LazItemType::kWavePacket14:
        throw source.errorAt(item_at, name + " is " + lazItemName(item.type) +
                                          ": waveform packets (point formats 4, 5, 9 and 10) are not read");
      case LazItemType::kByte:
      case LazItemType::kPoint10:
      case LazItemType::kGpsTime11:
      case LazItemType::kRgb12:
        throw source.errorAt(item_at, name + " is " + lazItemName(item.type) +
                                          ", an item of the point-wise coder, which the layered coder (compressor 3) "
                                          "does not code: a corrupt LAZ file");
      default:
        throw source.errorAt(item_at, name + " has type " + std::to_string(item.type) +
                                          ", which LASzip does not define: a corrupt or newer LAZ file");
    }
    if (item.version != 3 && item.version != 4) {
      throw source.errorAt(item_at + 4,
                           name + " is " + lazItemName(item.type) + " version " + std::to_string(item.version) +
                               ": the layered LAZ coder has versions 3 and 4 (a corrupt or newer file)");
    }
    if (!makeLazLayeredItemDecoder(item)) {
      throw source.errorAt(item_at + 2, name + " is " + lazItemName(item.type) + " of " + std::to_string(item.size) +
                                            " bytes, a size that item does not have (a corrupt LAZ header)");
    }
  }
  if (format < 6 || format > 8) {
    throw source.errorAt(at + kItemsAt, "point format " + std::to_string(format) +
                                            " compressed with the layered LAZ coder: Plumb reads layered LAZ point "
                                            "formats 6 to 8 (9 and 10 carry waveforms; 0 to 5 take the point-wise "
                                            "coder)");
  }
  const std::vector<LazItem> expected = itemsOfFormat14(format, record_length);
  bool match = expected.size() == vlr.items.size();
  for (std::size_t i = 0; match && i < expected.size(); ++i) {
    match = expected[i].type == vlr.items[i].type && expected[i].size == vlr.items[i].size;
  }
  if (!match) {
    throw source.errorAt(at + kItemsAt, "the items of " + where + " (" + itemList(vlr.items) +
                                            ") are not the records of point format " + std::to_string(format) +
                                            " with " + std::to_string(record_length) + " bytes (" + itemList(expected) +
                                            "): a corrupt LAZ header");
  }
}

}  // namespace

std::string LaszipVlr::writer() const {
  return "LASzip " + std::to_string(version_major) + "." + std::to_string(version_minor) + "r" +
         std::to_string(version_revision);
}

std::string lazItemName(std::uint16_t type) {
  switch (static_cast<LazItemType>(type)) {
    case LazItemType::kByte:
      return "BYTE";
    case LazItemType::kPoint10:
      return "POINT10";
    case LazItemType::kGpsTime11:
      return "GPSTIME11";
    case LazItemType::kRgb12:
      return "RGB12";
    case LazItemType::kWavePacket13:
      return "WAVEPACKET13";
    case LazItemType::kPoint14:
      return "POINT14";
    case LazItemType::kRgb14:
      return "RGB14";
    case LazItemType::kRgbNir14:
      return "RGBNIR14";
    case LazItemType::kWavePacket14:
      return "WAVEPACKET14";
    case LazItemType::kByte14:
      return "BYTE14";
  }
  return "type " + std::to_string(type);
}

LaszipVlr readLaszipVlr(std::span<const std::byte> payload, std::uint64_t at, const FileSource& source, unsigned format,
                        std::size_t record_length) {
  const std::string where = "the laszip VLR";
  if (payload.size() < kItemsAt + kItemBytes || (payload.size() - kItemsAt) % kItemBytes != 0) {
    throw source.errorAt(at, where + " has " + std::to_string(payload.size()) +
                                 " bytes, where it has 34 plus 6 per item (a corrupt LAZ header)");
  }
  const std::size_t item_count = (payload.size() - kItemsAt) / kItemBytes;
  const auto declared_items = loadLittleEndian<std::uint16_t>(payload.data() + kItemCountAt);
  if (declared_items != item_count) {
    throw source.errorAt(at + kItemCountAt, where + " declares " + std::to_string(declared_items) +
                                                " items but holds " + std::to_string(item_count) +
                                                " (a corrupt LAZ header)");
  }

  LaszipVlr vlr;
  const auto compressor = loadLittleEndian<std::uint16_t>(payload.data() + kCompressorAt);
  if (compressor > static_cast<std::uint16_t>(LazCompressor::kLayeredChunked)) {
    throw source.errorAt(at + kCompressorAt,
                         where + " names compressor " + std::to_string(compressor) +
                             ", which LASzip does not define (0 to 3): a corrupt or newer LAZ file");
  }
  vlr.compressor = static_cast<LazCompressor>(compressor);
  vlr.coder = loadLittleEndian<std::uint16_t>(payload.data() + kCoderAt);
  vlr.version_major = loadLittleEndian<std::uint8_t>(payload.data() + kVersionMajorAt);
  vlr.version_minor = loadLittleEndian<std::uint8_t>(payload.data() + kVersionMinorAt);
  vlr.version_revision = loadLittleEndian<std::uint16_t>(payload.data() + kVersionRevisionAt);
  vlr.chunk_size = loadLittleEndian<std::uint32_t>(payload.data() + kChunkSizeAt);
  for (std::size_t i = 0; i < item_count; ++i) {
    const std::byte* item = payload.data() + kItemsAt + kItemBytes * i;
    vlr.items.push_back({loadLittleEndian<std::uint16_t>(item), loadLittleEndian<std::uint16_t>(item + 2),
                         loadLittleEndian<std::uint16_t>(item + 4)});
  }

  if (vlr.coder != kArithmeticCoder) {
    throw source.errorAt(at + kCoderAt, where + " names coder " + std::to_string(vlr.coder) +
                                            ", where LASzip has only coder 0 (arithmetic): a corrupt LAZ file");
  }
  if (vlr.compressor == LazCompressor::kNone) return vlr;  // raw records: the items do not matter
  if (vlr.compressor == LazCompressor::kLayeredChunked) {
    checkLayeredItems(vlr, at, source, format, record_length);
    return vlr;
  }

  // Each item on its own, then the list against the point format.
  for (std::size_t i = 0; i < item_count; ++i) {
    const LazItem& item = vlr.items[i];
    const std::uint64_t item_at = at + kItemsAt + kItemBytes * i;
    const std::string name = "item " + std::to_string(i + 1) + " of " + where;
    const auto type = static_cast<LazItemType>(item.type);
    switch (type) {
      case LazItemType::kByte:
      case LazItemType::kPoint10:
      case LazItemType::kGpsTime11:
      case LazItemType::kRgb12:
        break;
      case LazItemType::kWavePacket13:
        throw source.errorAt(item_at, name + " is WAVEPACKET13: waveform packets (point formats 4 and 5) are not read");
      case LazItemType::kPoint14:
      case LazItemType::kRgb14:
      case LazItemType::kRgbNir14:
      case LazItemType::kWavePacket14:
      case LazItemType::kByte14:
        throw source.errorAt(item_at, name + " is " + lazItemName(item.type) +
                                          ", an item of LAS 1.4 point formats 6 to 10, which the point-wise coder "
                                          "does not code: a corrupt LAZ file");
      default:
        throw source.errorAt(item_at, name + " has type " + std::to_string(item.type) +
                                          ", which LASzip does not define: a corrupt or newer LAZ file");
    }
    if (item.version != 1 && item.version != 2) {
      throw source.errorAt(item_at + 4,
                           name + " is " + lazItemName(item.type) + " version " + std::to_string(item.version) +
                               ": the point-wise LAZ coder has versions 1 and 2 (a corrupt or newer file)");
    }
    if (!makeLazItemDecoder(item)) {
      throw source.errorAt(item_at + 2, name + " is " + lazItemName(item.type) + " of " + std::to_string(item.size) +
                                            " bytes, a size that item does not have (a corrupt LAZ header)");
    }
  }
  if (format > 3) {
    throw source.errorAt(at + kItemsAt, "point format " + std::to_string(format) +
                                            " compressed with the point-wise LAZ coder: Plumb reads LAZ point formats "
                                            "0 to 3 (formats 4 and 5 carry waveforms; 6 to 10 take the layered coder)");
  }
  const std::vector<LazItem> expected = itemsOfFormat(format, record_length);
  bool match = expected.size() == vlr.items.size();
  for (std::size_t i = 0; match && i < expected.size(); ++i) {
    match = expected[i].type == vlr.items[i].type && expected[i].size == vlr.items[i].size;
  }
  if (!match) {
    throw source.errorAt(at + kItemsAt, "the items of " + where + " (" + itemList(vlr.items) +
                                            ") are not the records of point format " + std::to_string(format) +
                                            " with " + std::to_string(record_length) + " bytes (" + itemList(expected) +
                                            "): a corrupt LAZ header");
  }
  return vlr;
}

}  // namespace plumb::io
