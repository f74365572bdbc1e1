#include "cad/dxf_document.h"

#include <Eigen/Geometry>
#include <algorithm>
#include <cassert>
#include <cctype>
#include <cmath>
#include <cstdio>

#include "cad/number_text.h"

namespace plumb::cad {
namespace {

// The handles of the drawing's fixed objects; layers follow, then the entities.
enum Handle : std::uint64_t {
  kVportTable = 1,
  kLtypeTable,
  kLayerTable,
  kStyleTable,
  kViewTable,
  kUcsTable,
  kAppidTable,
  kDimstyleTable,
  kBlockRecordTable,
  kActiveVport,
  kByBlock,
  kByLayer,
  kContinuous,
  kStandardStyle,
  kAcadAppid,
  kStandardDimstyle,
  kModelSpaceRecord,
  kPaperSpaceRecord,
  kModelSpaceBlock,
  kModelSpaceEnd,
  kPaperSpaceBlock,
  kPaperSpaceEnd,
  kRootDictionary,
  kGroupDictionary,
  kFirstLayer,  // layer 0, then the drawing's layers
};

// One group: its code right-aligned in three columns, as AutoCAD writes it, then its value.
void putCode(std::string& out, int group) {
  char text[8];
  std::snprintf(text, sizeof text, "%3d\n", group);
  out += text;
}
void putText(std::string& out, int group, std::string_view value) {
  putCode(out, group);
  out.append(value).append("\n");
}
void putInt(std::string& out, int group, long long value) {
  putCode(out, group);
  out += std::to_string(value) + "\n";
}
void putReal(std::string& out, int group, double value) {
  putCode(out, group);
  appendNumber(out, value);
  out += "\n";
}
void putHandle(std::string& out, int group, std::uint64_t value) {
  char hex[24];
  std::snprintf(hex, sizeof hex, "%llX", static_cast<unsigned long long>(value));
  putText(out, group, hex);
}
// A point or vector: x at `group`, y at group + 10, z at group + 20.
void putPoint(std::string& out, int group, const Eigen::Vector3d& p) {
  putReal(out, group, p.x());
  putReal(out, group + 10, p.y());
  putReal(out, group + 20, p.z());
}

void sectionStart(std::string& out, std::string_view name) {
  putText(out, 0, "SECTION");
  putText(out, 2, name);
}
void sectionEnd(std::string& out) {
  putText(out, 0, "ENDSEC");
}

void tableStart(std::string& out, std::string_view name, std::uint64_t table, std::size_t entries) {
  putText(out, 0, "TABLE");
  putText(out, 2, name);
  putHandle(out, 5, table);
  putHandle(out, 330, 0);
  putText(out, 100, "AcDbSymbolTable");
  putInt(out, 70, static_cast<long long>(entries));
  if (name == "DIMSTYLE") putText(out, 100, "AcDbDimStyleTable");
}
void tableEnd(std::string& out) {
  putText(out, 0, "ENDTAB");
}

// The groups every table record starts with; flags (70) are left to the caller.
void recordStart(std::string& out, std::string_view type, std::uint64_t own, std::uint64_t table,
                 std::string_view subclass, std::string_view name) {
  putText(out, 0, type);
  putHandle(out, type == "DIMSTYLE" ? 105 : 5, own);
  putHandle(out, 330, table);
  putText(out, 100, "AcDbSymbolTableRecord");
  putText(out, 100, subclass);
  putText(out, 2, name);
}

void linetype(std::string& out, std::uint64_t own, std::string_view name, std::string_view description) {
  recordStart(out, "LTYPE", own, kLtypeTable, "AcDbLinetypeTableRecord", name);
  putInt(out, 70, 0);
  putText(out, 3, description);
  putInt(out, 72, 65);  // alignment 'A', the only one there is
  putInt(out, 73, 0);   // no dashes: continuous
  putReal(out, 40, 0.0);
}

void layerRecord(std::string& out, std::uint64_t own, const DxfLayer& layer) {
  recordStart(out, "LAYER", own, kLayerTable, "AcDbLayerTableRecord", layer.name);
  putInt(out, 70, 0);
  putInt(out, 62, layer.colour);
  putText(out, 6, "Continuous");
  putInt(out, 370, -3);  // the default lineweight
}

void block(std::string& out, std::uint64_t begin, std::uint64_t end, std::uint64_t record, std::string_view name,
           bool paper) {
  putText(out, 0, "BLOCK");
  putHandle(out, 5, begin);
  putHandle(out, 330, record);
  putText(out, 100, "AcDbEntity");
  if (paper) putInt(out, 67, 1);
  putText(out, 8, "0");
  putText(out, 100, "AcDbBlockBegin");
  putText(out, 2, name);
  putInt(out, 70, 0);
  putPoint(out, 10, Eigen::Vector3d::Zero());
  putText(out, 3, name);
  putText(out, 1, "");
  putText(out, 0, "ENDBLK");
  putHandle(out, 5, end);
  putHandle(out, 330, record);
  putText(out, 100, "AcDbEntity");
  if (paper) putInt(out, 67, 1);
  putText(out, 8, "0");
  putText(out, 100, "AcDbBlockEnd");
}

[[maybe_unused]] bool validLayerName(std::string_view name) {  // asserted only
  return !name.empty() && std::all_of(name.begin(), name.end(), [](char c) {
    return std::isalnum(static_cast<unsigned char>(c)) != 0 || c == '_' || c == '-';
  });
}

}  // namespace

DxfOcs dxfOcs(const Eigen::Vector3d& normal) {
  assert(std::abs(normal.norm() - 1.0) < 1e-9 && "dxfOcs needs a unit extrusion direction");
  // The arbitrary axis algorithm of the DXF reference: near the world z axis (both x and y
  // components below 1/64) the OCS x axis is world y cross normal, elsewhere world z cross normal.
  constexpr double kNearZ = 1.0 / 64.0;
  const bool near_z = std::abs(normal.x()) < kNearZ && std::abs(normal.y()) < kNearZ;
  const Eigen::Vector3d x_axis =
      (near_z ? Eigen::Vector3d::UnitY() : Eigen::Vector3d::UnitZ()).cross(normal).normalized();
  return {x_axis, normal.cross(x_axis).normalized()};
}

DxfDocument::DxfDocument(std::vector<DxfLayer> layers)
    : layers_(std::move(layers)), next_handle_(kFirstLayer + 1 + layers_.size()) {
  for ([[maybe_unused]] const DxfLayer& layer : layers_) {
    assert(validLayerName(layer.name) && "DXF layer names here are letters, digits, '_' and '-'");
    assert(layer.colour >= 1 && layer.colour <= 255 && "a DXF layer colour is an AutoCAD colour index, 1 to 255");
  }
}

std::string DxfDocument::entityStart(std::string_view type, std::string_view layer, std::string_view subclass) {
  assert(std::any_of(layers_.begin(), layers_.end(), [&](const DxfLayer& known) { return known.name == layer; }) &&
         "DxfDocument: an entity on a layer the constructor was not given");
  std::string out;
  putText(out, 0, type);
  putHandle(out, 5, next_handle_++);
  putHandle(out, 330, kModelSpaceRecord);
  putText(out, 100, "AcDbEntity");
  putText(out, 8, layer);
  putText(out, 100, subclass);
  return out;
}

void DxfDocument::extend(const Eigen::Vector3d& p) {
  assert(p.allFinite() && "DxfDocument: coordinates must be finite");
  min_ = empty_ ? p : min_.cwiseMin(p);
  max_ = empty_ ? p : max_.cwiseMax(p);
  empty_ = false;
}

void DxfDocument::addFace(std::string_view layer, const Eigen::Vector3d& a, const Eigen::Vector3d& b,
                          const Eigen::Vector3d& c) {
  std::string out = entityStart("3DFACE", layer, "AcDbFace");
  putPoint(out, 10, a);
  putPoint(out, 11, b);
  putPoint(out, 12, c);
  putPoint(out, 13, c);  // a triangle repeats its third corner as the fourth
  putInt(out, 70, 0);
  for (const Eigen::Vector3d* p : {&a, &b, &c}) extend(*p);
  entities_ += out;
}

void DxfDocument::addPolyline(std::string_view layer, std::span<const Eigen::Vector3d> ring,
                              const Eigen::Vector3d& normal, bool closed) {
  assert(ring.size() >= 2 && "a polyline needs at least 2 vertices");
  const DxfOcs ocs = dxfOcs(normal);
  double elevation = 0.0;
  for (const Eigen::Vector3d& p : ring) elevation += normal.dot(p);
  elevation /= static_cast<double>(ring.size());

  std::string out = entityStart("LWPOLYLINE", layer, "AcDbPolyline");
  putInt(out, 90, static_cast<long long>(ring.size()));
  putInt(out, 70, closed ? 1 : 0);
  putReal(out, 38, elevation);
  for (const Eigen::Vector3d& p : ring) {
    putReal(out, 10, ocs.x_axis.dot(p));
    putReal(out, 20, ocs.y_axis.dot(p));
    extend(p);
  }
  putPoint(out, 210, normal);
  entities_ += out;
}

void DxfDocument::addLine(std::string_view layer, const Eigen::Vector3d& start, const Eigen::Vector3d& end) {
  std::string out = entityStart("LINE", layer, "AcDbLine");
  putPoint(out, 10, start);
  putPoint(out, 11, end);
  extend(start);
  extend(end);
  entities_ += out;
}

void DxfDocument::addPoint(std::string_view layer, const Eigen::Vector3d& position) {
  std::string out = entityStart("POINT", layer, "AcDbPoint");
  putPoint(out, 10, position);
  extend(position);
  entities_ += out;
}

std::string DxfDocument::text() const {
  std::string out;
  sectionStart(out, "HEADER");
  putText(out, 9, "$ACADVER");
  putText(out, 1, "AC1015");
  putText(out, 9, "$DWGCODEPAGE");
  putText(out, 3, "ANSI_1252");
  putText(out, 9, "$INSBASE");
  putPoint(out, 10, Eigen::Vector3d::Zero());
  putText(out, 9, "$EXTMIN");
  putPoint(out, 10, min_);
  putText(out, 9, "$EXTMAX");
  putPoint(out, 10, max_);
  putText(out, 9, "$INSUNITS");
  putInt(out, 70, 6);  // metres
  putText(out, 9, "$MEASUREMENT");
  putInt(out, 70, 1);  // metric
  putText(out, 9, "$HANDSEED");
  putHandle(out, 5, next_handle_);
  sectionEnd(out);

  sectionStart(out, "CLASSES");
  sectionEnd(out);

  sectionStart(out, "TABLES");
  // The active viewport looks down on the extents from above, so a viewer opens on the drawing
  // even at UTM coordinates.
  tableStart(out, "VPORT", kVportTable, 1);
  recordStart(out, "VPORT", kActiveVport, kVportTable, "AcDbViewportTableRecord", "*ACTIVE");
  putInt(out, 70, 0);
  const Eigen::Vector3d centre = 0.5 * (min_ + max_), size = max_ - min_;
  constexpr double kAspect = 1.5;
  const double height = std::max({1.1 * size.y(), 1.1 * size.x() / kAspect, 1.0});
  putReal(out, 10, 0.0);
  putReal(out, 20, 0.0);
  putReal(out, 11, 1.0);
  putReal(out, 21, 1.0);
  putReal(out, 12, centre.x());
  putReal(out, 22, centre.y());
  putReal(out, 13, 0.0);
  putReal(out, 23, 0.0);
  putReal(out, 14, 1.0);
  putReal(out, 24, 1.0);
  putReal(out, 15, 1.0);
  putReal(out, 25, 1.0);
  putPoint(out, 16, Eigen::Vector3d::UnitZ());  // view direction: from above
  putPoint(out, 17, Eigen::Vector3d::Zero());   // view target
  putReal(out, 40, height);
  putReal(out, 41, kAspect);
  putReal(out, 42, 50.0);  // lens length, mm
  putReal(out, 43, 0.0);
  putReal(out, 44, 0.0);
  putReal(out, 50, 0.0);
  putReal(out, 51, 0.0);
  putInt(out, 71, 0);
  putInt(out, 72, 100);
  putInt(out, 73, 1);
  putInt(out, 74, 3);
  putInt(out, 75, 0);
  putInt(out, 76, 0);
  putInt(out, 77, 0);
  putInt(out, 78, 0);
  tableEnd(out);

  tableStart(out, "LTYPE", kLtypeTable, 3);
  linetype(out, kByBlock, "ByBlock", "");
  linetype(out, kByLayer, "ByLayer", "");
  linetype(out, kContinuous, "Continuous", "Solid line");
  tableEnd(out);

  tableStart(out, "LAYER", kLayerTable, layers_.size() + 1);
  layerRecord(out, kFirstLayer, DxfLayer{"0", 7});
  for (std::size_t i = 0; i < layers_.size(); ++i) layerRecord(out, kFirstLayer + 1 + i, layers_[i]);
  tableEnd(out);

  tableStart(out, "STYLE", kStyleTable, 1);
  recordStart(out, "STYLE", kStandardStyle, kStyleTable, "AcDbTextStyleTableRecord", "Standard");
  putInt(out, 70, 0);
  putReal(out, 40, 0.0);  // no fixed height
  putReal(out, 41, 1.0);  // width factor
  putReal(out, 50, 0.0);  // oblique angle
  putInt(out, 71, 0);
  putReal(out, 42, 2.5);  // last height used
  putText(out, 3, "txt");
  putText(out, 4, "");
  tableEnd(out);

  tableStart(out, "VIEW", kViewTable, 0);
  tableEnd(out);
  tableStart(out, "UCS", kUcsTable, 0);
  tableEnd(out);

  tableStart(out, "APPID", kAppidTable, 1);
  recordStart(out, "APPID", kAcadAppid, kAppidTable, "AcDbRegAppTableRecord", "ACAD");
  putInt(out, 70, 0);
  tableEnd(out);

  tableStart(out, "DIMSTYLE", kDimstyleTable, 1);
  recordStart(out, "DIMSTYLE", kStandardDimstyle, kDimstyleTable, "AcDbDimStyleTableRecord", "Standard");
  putInt(out, 70, 0);
  tableEnd(out);

  tableStart(out, "BLOCK_RECORD", kBlockRecordTable, 2);
  recordStart(out, "BLOCK_RECORD", kModelSpaceRecord, kBlockRecordTable, "AcDbBlockTableRecord", "*Model_Space");
  recordStart(out, "BLOCK_RECORD", kPaperSpaceRecord, kBlockRecordTable, "AcDbBlockTableRecord", "*Paper_Space");
  tableEnd(out);
  sectionEnd(out);

  sectionStart(out, "BLOCKS");
  block(out, kModelSpaceBlock, kModelSpaceEnd, kModelSpaceRecord, "*Model_Space", false);
  block(out, kPaperSpaceBlock, kPaperSpaceEnd, kPaperSpaceRecord, "*Paper_Space", true);
  sectionEnd(out);

  sectionStart(out, "ENTITIES");
  out += entities_;
  sectionEnd(out);

  sectionStart(out, "OBJECTS");
  putText(out, 0, "DICTIONARY");
  putHandle(out, 5, kRootDictionary);
  putHandle(out, 330, 0);
  putText(out, 100, "AcDbDictionary");
  putInt(out, 281, 1);
  putText(out, 3, "ACAD_GROUP");
  putHandle(out, 350, kGroupDictionary);
  putText(out, 0, "DICTIONARY");
  putHandle(out, 5, kGroupDictionary);
  putHandle(out, 330, kRootDictionary);
  putText(out, 100, "AcDbDictionary");
  putInt(out, 281, 1);
  sectionEnd(out);
  putText(out, 0, "EOF");
  return out;
}

}  // namespace plumb::cad
