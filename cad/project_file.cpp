#include "cad/project_file.h"

#include <cmath>
#include <string_view>

#include "cad/json_place.h"
#include "cad/measurement.h"
#include "cad/project_validation.h"
#include "cad/text_file.h"
#include "engine/core/atomic_file.h"
#include "engine/core/error.h"
#include "engine/view/camera_json.h"

namespace plumb::cad {
namespace {

using Json = nlohmann::json;
using OrderedJson = nlohmann::ordered_json;

constexpr std::string_view kFormat = "plumb-project";
constexpr std::string_view kWhat = "Plumb project file";

// Reading. Each item's fields are checked against the list docs/project-file.md gives.

std::string optionalString(const JsonPlace& at, std::string_view name) {
  const auto field = at.optionalField(name);
  return field ? field->string() : std::string();
}

ItemId optionalReference(const JsonPlace& at, std::string_view name) {
  const auto field = at.optionalField(name);
  return field ? field->whole() : kNoItem;
}

template <typename Read>
auto readList(const JsonPlace& root, std::string_view name, Read read) {
  std::vector<decltype(read(root))> items;
  if (const auto list = root.optionalField(name)) {
    const std::size_t count = list->expectArray();
    items.reserve(count);
    for (std::size_t i = 0; i < count; ++i) items.push_back(read(list->element(i)));
  }
  return items;
}

template <typename Value, std::size_t N, typename Read>
std::array<Value, N> readArray(const JsonPlace& at, Read read) {
  at.expectArray(N);
  std::array<Value, N> values{};
  for (std::size_t i = 0; i < N; ++i) values[i] = read(at.element(i));
  return values;
}

std::vector<Eigen::Vector2d> readPoints2(const JsonPlace& at) {
  std::vector<Eigen::Vector2d> points(at.expectArray());
  for (std::size_t i = 0; i < points.size(); ++i) points[i] = at.element(i).vector2();
  return points;
}

std::vector<Eigen::Vector3d> readPoints3(const JsonPlace& at) {
  std::vector<Eigen::Vector3d> points(at.expectArray());
  for (std::size_t i = 0; i < points.size(); ++i) points[i] = at.element(i).vector3();
  return points;
}

Group readGroup(const JsonPlace& at) {
  at.expectObject({"id", "name"});
  return {at.field("id").id(), optionalString(at, "name")};
}

reco::Plane readPlane(const JsonPlace& at) {
  at.expectObject(
      {"normal", "tangent", "bitangent", "centroid", "offset", "lambda0", "lambda1", "lambda2", "point_count", "rms"});
  reco::Plane plane;
  plane.valid = true;
  plane.normal = at.field("normal").vector3();
  plane.tangent = at.field("tangent").vector3();
  plane.bitangent = at.field("bitangent").vector3();
  plane.centroid = at.field("centroid").vector3();
  plane.offset = at.field("offset").number();
  plane.lambda0 = at.field("lambda0").number();
  plane.lambda1 = at.field("lambda1").number();
  plane.lambda2 = at.field("lambda2").number();
  plane.point_count = at.field("point_count").whole();
  plane.rms = at.field("rms").number();
  return plane;
}

reco::PlaneOutline readOutline(const JsonPlace& at) {
  at.expectObject(
      {"origin", "axis_u", "axis_v", "rings", "vertices", "triangles", "area_m2", "cell_m", "raster_cells"});
  reco::PlaneOutline outline;
  outline.origin = at.field("origin").vector3();
  outline.axis_u = at.field("axis_u").vector3();
  outline.axis_v = at.field("axis_v").vector3();
  reco::Outline& shape = outline.shape;
  const JsonPlace rings = at.field("rings");
  shape.rings.resize(rings.expectArray());
  for (std::size_t r = 0; r < shape.rings.size(); ++r) shape.rings[r] = readPoints2(rings.element(r));
  shape.vertices = readPoints2(at.field("vertices"));
  const JsonPlace triangles = at.field("triangles");
  shape.triangles.resize(triangles.expectArray());
  for (std::size_t t = 0; t < shape.triangles.size(); ++t) {
    shape.triangles[t] =
        readArray<std::uint32_t, 3>(triangles.element(t), [](const JsonPlace& v) { return v.index(); });
  }
  shape.area_m2 = at.field("area_m2").number();
  shape.cell_m = at.field("cell_m").number();
  const auto raster =
      readArray<std::uint32_t, 2>(at.field("raster_cells"), [](const JsonPlace& v) { return v.index(); });
  shape.raster_width_cells = raster[0];
  shape.raster_height_cells = raster[1];
  return outline;
}

Segment readSegment(const JsonPlace& at) {
  at.expectObject({"id", "name", "group", "plane", "outline"});
  Segment segment;
  segment.id = at.field("id").id();
  segment.name = optionalString(at, "name");
  segment.group = optionalReference(at, "group");
  segment.plane = readPlane(at.field("plane"));
  if (const auto outline = at.optionalField("outline")) segment.outline = readOutline(*outline);
  return segment;
}

Edge readEdge(const JsonPlace& at) {
  at.expectObject({"id", "name", "group", "segments", "start", "end"});
  Edge edge;
  edge.id = at.field("id").id();
  edge.name = optionalString(at, "name");
  edge.group = optionalReference(at, "group");
  edge.segments = readArray<ItemId, 2>(at.field("segments"), [](const JsonPlace& v) { return v.whole(); });
  edge.start = at.field("start").vector3();
  edge.end = at.field("end").vector3();
  return edge;
}

Corner readCorner(const JsonPlace& at) {
  at.expectObject({"id", "name", "group", "segments", "position", "support"});
  Corner corner;
  corner.id = at.field("id").id();
  corner.name = optionalString(at, "name");
  corner.group = optionalReference(at, "group");
  corner.segments = readArray<ItemId, 3>(at.field("segments"), [](const JsonPlace& v) { return v.whole(); });
  corner.position = at.field("position").vector3();
  corner.support = readArray<double, 3>(at.field("support"), [](const JsonPlace& v) { return v.number(); });
  return corner;
}

Polygon readPolygon(const JsonPlace& at) {
  at.expectObject({"id", "name", "group", "plane", "vertices", "extrusion"});
  Polygon polygon;
  polygon.id = at.field("id").id();
  polygon.name = optionalString(at, "name");
  polygon.group = optionalReference(at, "group");
  polygon.plane = optionalReference(at, "plane");
  polygon.vertices = readPoints3(at.field("vertices"));
  if (const auto extrusion = at.optionalField("extrusion")) polygon.extrusion = extrusion->vector3();
  return polygon;
}

MeasureTerm readMeasureTerm(const JsonPlace& at) {
  at.expectObject({"kind", "point", "direction", "ring"});
  MeasureTerm term;
  const JsonPlace kind = at.field("kind");
  const std::optional<MeasureTerm::Kind> named = measureTermKindNamed(kind.string());
  if (!named) throw kind.error("expected \"point\", \"plane\", \"line\" or \"polygon\"");
  term.kind = *named;
  // Only the fields of its kind: a point's direction would be silently dropped otherwise.
  if (term.kind == MeasureTerm::Kind::kPolygon) {
    at.expectObject({"kind", "ring"});
    term.ring = readPoints3(at.field("ring"));
  } else if (term.kind == MeasureTerm::Kind::kPoint) {
    at.expectObject({"kind", "point"});
    term.point = at.field("point").vector3();
  } else {
    at.expectObject({"kind", "point", "direction"});
    term.point = at.field("point").vector3();
    term.direction = at.field("direction").vector3();
  }
  return term;
}

Measurement readMeasurement(const JsonPlace& at) {
  at.expectObject({"id", "name", "group", "kind", "terms", "sources"});
  Measurement measurement;
  measurement.id = at.field("id").id();
  measurement.name = optionalString(at, "name");
  measurement.group = optionalReference(at, "group");
  const JsonPlace kind = at.field("kind");
  const std::optional<MeasureKind> named = measureKindNamed(kind.string());
  if (!named) {
    throw kind.error(
        "expected \"distance\", \"angle\", \"point_to_plane\", \"between_planes\", \"height\" or \"area\"");
  }
  measurement.kind = *named;
  const JsonPlace terms = at.field("terms");
  measurement.terms.resize(terms.expectArray());
  for (std::size_t i = 0; i < measurement.terms.size(); ++i) measurement.terms[i] = readMeasureTerm(terms.element(i));
  const JsonPlace sources = at.field("sources");
  measurement.sources.resize(sources.expectArray());
  for (std::size_t i = 0; i < measurement.sources.size(); ++i) measurement.sources[i] = sources.element(i).whole();
  return measurement;
}

// Writing, in the order of docs/project-file.md (an ordered_json keeps it).

OrderedJson vector(const Eigen::Vector3d& v) {
  return OrderedJson::array({v.x(), v.y(), v.z()});
}
OrderedJson vector(const Eigen::Vector2d& v) {
  return OrderedJson::array({v.x(), v.y()});
}

OrderedJson planeJson(const reco::Plane& plane) {
  OrderedJson json;
  json["normal"] = vector(plane.normal);
  json["tangent"] = vector(plane.tangent);
  json["bitangent"] = vector(plane.bitangent);
  json["centroid"] = vector(plane.centroid);
  json["offset"] = plane.offset;
  json["lambda0"] = plane.lambda0;
  json["lambda1"] = plane.lambda1;
  json["lambda2"] = plane.lambda2;
  json["point_count"] = plane.point_count;
  json["rms"] = plane.rms;
  return json;
}

OrderedJson pointsJson(const std::vector<Eigen::Vector2d>& points) {
  OrderedJson json = OrderedJson::array();
  for (const Eigen::Vector2d& p : points) json.push_back(vector(p));
  return json;
}

OrderedJson outlineJson(const reco::PlaneOutline& outline) {
  OrderedJson json;
  json["origin"] = vector(outline.origin);
  json["axis_u"] = vector(outline.axis_u);
  json["axis_v"] = vector(outline.axis_v);
  json["rings"] = OrderedJson::array();
  for (const auto& ring : outline.shape.rings) json["rings"].push_back(pointsJson(ring));
  json["vertices"] = pointsJson(outline.shape.vertices);
  json["triangles"] = OrderedJson::array();
  for (const auto& [a, b, c] : outline.shape.triangles) json["triangles"].push_back({a, b, c});
  json["area_m2"] = outline.shape.area_m2;
  json["cell_m"] = outline.shape.cell_m;
  json["raster_cells"] = {outline.shape.raster_width_cells, outline.shape.raster_height_cells};
  return json;
}

// The fields every item starts with.
OrderedJson itemJson(ItemId id, const std::string& name, ItemId group) {
  OrderedJson json;
  json["id"] = id;
  json["name"] = name;
  json["group"] = group;
  return json;
}

OrderedJson measureTermJson(const MeasureTerm& term) {
  OrderedJson json;
  json["kind"] = measureTermKindName(term.kind);
  if (term.kind == MeasureTerm::Kind::kPolygon) {
    json["ring"] = OrderedJson::array();
    for (const Eigen::Vector3d& v : term.ring) json["ring"].push_back(vector(v));
  } else {
    json["point"] = vector(term.point);
    if (term.kind != MeasureTerm::Kind::kPoint) json["direction"] = vector(term.direction);
  }
  return json;
}

OrderedJson sectionJson(const view::ClipSettings& section) {
  OrderedJson json;
  if (section.slice) json["slice"] = {{"bottom_z", section.slice_bottom_z}, {"thickness", section.slice_thickness}};
  if (section.slab) {
    json["slab"] = {{"point", vector(section.slab->point)},
                    {"normal", vector(section.slab->normal)},
                    {"thickness", section.slab->thickness}};
  }
  if (section.box) {
    json["box"] = {{"centre", vector(section.box->centre)},
                   {"size", vector(Eigen::Vector3d(2.0 * section.box->half_size))},
                   {"turn_rad", section.box->yaw_rad},
                   {"keep_outside", section.keep_outside_box}};
  }
  json["planes"] = OrderedJson::array();
  for (const view::ClipPlane& plane : section.planes) {
    json["planes"].push_back({{"point", vector(plane.point)}, {"normal", vector(plane.normal)}});
  }
  return json;
}

view::ClipSettings readSection(const JsonPlace& at) {
  at.expectObject({"slice", "slab", "box", "planes"});
  view::ClipSettings section;
  if (const auto slice = at.optionalField("slice")) {
    slice->expectObject({"bottom_z", "thickness"});
    section.slice = true;
    section.slice_bottom_z = slice->field("bottom_z").number();
    section.slice_thickness = slice->field("thickness").number();
    if (!(section.slice_thickness > 0.0)) throw slice->field("thickness").error("must be above 0");
  }
  if (const auto slab = at.optionalField("slab")) {
    slab->expectObject({"point", "normal", "thickness"});
    const Eigen::Vector3d normal = slab->field("normal").vector3();
    if (std::abs(normal.norm() - 1.0) > 1e-6) throw slab->field("normal").error("must be a unit vector");
    const double thickness = slab->field("thickness").number();
    if (!(thickness > 0.0)) throw slab->field("thickness").error("must be above 0");
    section.slab = view::ClipSlab{slab->field("point").vector3(), normal, thickness};
  }
  if (const auto box = at.optionalField("box")) {
    box->expectObject({"centre", "size", "turn_rad", "keep_outside"});
    const Eigen::Vector3d size = box->field("size").vector3();
    if (!(size.minCoeff() > 0.0)) throw box->field("size").error("each size must be above 0");
    section.box = view::ClipBox{box->field("centre").vector3(), 0.5 * size, box->field("turn_rad").number()};
    const JsonPlace outside = box->field("keep_outside");
    if (!outside.value().is_boolean()) throw outside.error("expected true or false");
    section.keep_outside_box = outside.value().get<bool>();
  }
  if (const auto planes = at.optionalField("planes")) {
    const std::size_t count = planes->expectArray();
    for (std::size_t i = 0; i < count; ++i) {
      const JsonPlace plane = planes->element(i);
      plane.expectObject({"point", "normal"});
      const Eigen::Vector3d normal = plane.field("normal").vector3();
      if (std::abs(normal.norm() - 1.0) > 1e-6) throw plane.field("normal").error("must be a unit vector");
      section.planes.push_back({plane.field("point").vector3(), normal});
    }
  }
  try {
    view::checkClipRegion(section.region(), "section");
  } catch (const Error& error) {
    throw at.error(error.what());
  }
  return section;
}

OrderedJson projectJson(const Project& project) {
  OrderedJson json;
  json["format"] = kFormat;
  // The oldest version that holds the project, so that older builds still read what they can.
  json["version"] = project.measurements.empty() ? 2 : kProjectFileVersion;
  json["cloud"] = project.cloud_path;
  if (project.camera) json["camera"] = OrderedJson::parse(view::cameraJsonObject(*project.camera));
  if (project.section && project.section->active()) json["section"] = sectionJson(*project.section);
  json["groups"] = OrderedJson::array();
  for (const Group& group : project.groups) json["groups"].push_back({{"id", group.id}, {"name", group.name}});
  json["segments"] = OrderedJson::array();
  for (const Segment& segment : project.segments) {
    OrderedJson item = itemJson(segment.id, segment.name, segment.group);
    item["plane"] = planeJson(segment.plane);
    item["outline"] = outlineJson(segment.outline);
    json["segments"].push_back(std::move(item));
  }
  json["edges"] = OrderedJson::array();
  for (const Edge& edge : project.edges) {
    OrderedJson item = itemJson(edge.id, edge.name, edge.group);
    item["segments"] = edge.segments;
    item["start"] = vector(edge.start);
    item["end"] = vector(edge.end);
    json["edges"].push_back(std::move(item));
  }
  json["corners"] = OrderedJson::array();
  for (const Corner& corner : project.corners) {
    OrderedJson item = itemJson(corner.id, corner.name, corner.group);
    item["segments"] = corner.segments;
    item["position"] = vector(corner.position);
    item["support"] = corner.support;
    json["corners"].push_back(std::move(item));
  }
  json["polygons"] = OrderedJson::array();
  for (const Polygon& polygon : project.polygons) {
    OrderedJson item = itemJson(polygon.id, polygon.name, polygon.group);
    item["plane"] = polygon.plane;
    item["vertices"] = OrderedJson::array();
    for (const Eigen::Vector3d& v : polygon.vertices) item["vertices"].push_back(vector(v));
    item["extrusion"] = vector(polygon.extrusion);
    json["polygons"].push_back(std::move(item));
  }
  json["measurements"] = OrderedJson::array();
  for (const Measurement& measurement : project.measurements) {
    OrderedJson item = itemJson(measurement.id, measurement.name, measurement.group);
    item["kind"] = measureKindName(measurement.kind);
    item["terms"] = OrderedJson::array();
    for (const MeasureTerm& term : measurement.terms) item["terms"].push_back(measureTermJson(term));
    item["sources"] = measurement.sources;
    json["measurements"].push_back(std::move(item));
  }
  return json;
}

// Objects one field per line, arrays of numbers (a vector, a triangle) on one line, longer arrays
// one element per line: a file people can read and diff. nlohmann writes each double with the
// fewest digits that read back as the same bits.
void appendText(std::string& out, const OrderedJson& value, std::size_t indent) {
  constexpr std::size_t kLineLimit = 100;
  const std::string inner(indent + 2, ' ');
  if (value.is_object() && !value.empty()) {
    out += "{\n";
    bool first = true;
    for (const auto& [key, element] : value.items()) {
      if (!first) out += ",\n";
      out += inner;
      out += OrderedJson(key).dump();
      out += ": ";
      appendText(out, element, indent + 2);
      first = false;
    }
    out += '\n';
    out.append(indent, ' ');
    out += '}';
    return;
  }
  if (value.is_array() && !value.empty()) {
    bool flat = true;
    for (const auto& element : value) flat = flat && !element.is_object();
    std::string line = flat ? value.dump() : std::string();
    if (flat && line.size() <= kLineLimit) {
      out += line;
      return;
    }
    out += "[\n";
    bool first = true;
    for (const auto& element : value) {
      if (!first) out += ",\n";
      out += inner;
      appendText(out, element, indent + 2);
      first = false;
    }
    out += '\n';
    out.append(indent, ' ');
    out += ']';
    return;
  }
  out += value.dump();
}

}  // namespace

Project readProjectFile(const std::string& path) {
  const Json json = parseJsonFile(path, readTextFile(path, "project file"), kWhat);
  const JsonPlace root(path, json, "");
  if (!json.is_object()) {
    throw root.error(std::string("expected a JSON object (a Plumb project file), found ") + json.type_name());
  }
  // The format first: another kind of file is called that, not a list of unknown fields.
  const JsonPlace format = root.field("format");
  if (!format.value().is_string() || format.value().get<std::string>() != kFormat) {
    throw format.error("expected \"plumb-project\", found " + format.value().dump() + " (not a Plumb project file)");
  }
  const JsonPlace version = root.field("version");
  if (const std::uint64_t number = version.whole(1); number > static_cast<std::uint64_t>(kProjectFileVersion)) {
    throw version.error("written by a newer Plumb (version " + std::to_string(number) + "); this build reads up to " +
                        std::to_string(kProjectFileVersion) + ": update Plumb");
  }
  root.expectObject({"format", "version", "cloud", "camera", "section", "groups", "segments", "edges", "corners",
                     "polygons", "measurements"});

  Project project;
  project.cloud_path = optionalString(root, "cloud");
  if (const auto camera = root.optionalField("camera")) {
    project.camera = view::cameraFromJsonObject(camera->value().dump(), path, camera->place());
  }
  if (const auto section = root.optionalField("section")) project.section = readSection(*section);
  project.groups = readList(root, "groups", readGroup);
  project.segments = readList(root, "segments", readSegment);
  project.edges = readList(root, "edges", readEdge);
  project.corners = readList(root, "corners", readCorner);
  project.polygons = readList(root, "polygons", readPolygon);
  project.measurements = readList(root, "measurements", readMeasurement);

  if (const auto problem = findProjectProblem(project)) {
    throw fileError(path, "field '" + problem->place + "': " + problem->what);
  }
  return project;
}

void writeProjectFile(const Project& project, const std::string& path) {
  validateProject(project, path, "not writing an invalid project");
  std::string text;
  try {
    appendText(text, projectJson(project), 0);
  } catch (const nlohmann::json::type_error& error) {
    // nlohmann refuses to write a string that is not UTF-8.
    throw fileError(path, std::string("a name or the cloud path is not valid UTF-8 (") + error.what() + ")");
  }
  text += "\n";
  AtomicFile file(path);
  file.write(text.data(), text.size());
  file.commit();
}

}  // namespace plumb::cad
