#include "cad/export_csv.h"

#include <gtest/gtest.h>

#include "cad/measurement.h"
#include "tests/cad/sample_project.h"
#include "tests/support/temp_directory.h"

namespace plumb::cad {
namespace {

// An RFC 4180 reader: records end at CRLF outside quotes; a quoted field may hold commas, CR, LF
// and doubled quotes.
std::vector<std::vector<std::string>> parseCsv(const std::string& text) {
  std::vector<std::vector<std::string>> records;
  std::vector<std::string> record;
  std::string field;
  bool quoted = false;
  for (std::size_t i = 0; i < text.size(); ++i) {
    const char c = text[i];
    if (quoted) {
      if (c == '"' && i + 1 < text.size() && text[i + 1] == '"') {
        field += '"';
        ++i;
      } else if (c == '"') {
        quoted = false;
      } else {
        field += c;
      }
    } else if (c == '"') {
      EXPECT_TRUE(field.empty()) << "a quote inside an unquoted field at byte " << i;
      quoted = true;
    } else if (c == ',') {
      record.push_back(std::exchange(field, {}));
    } else if (c == '\r') {
      EXPECT_TRUE(i + 1 < text.size() && text[i + 1] == '\n') << "CR without LF at byte " << i;
      record.push_back(std::exchange(field, {}));
      records.push_back(std::exchange(record, {}));
      ++i;
    } else {
      EXPECT_NE(c, '\n') << "LF without CR at byte " << i;
      field += c;
    }
  }
  EXPECT_FALSE(quoted) << "an unterminated quote";
  EXPECT_TRUE(field.empty() && record.empty()) << "the last record does not end with CRLF";
  return records;
}

TEST(ExportCsv, CornersWithQuotedNamesAndFullPrecision) {
  plumb::test::TempDirectory directory;
  Project project = test::sampleProject();
  project.corners[1].name = "two\nlines";
  const std::string path = directory.file("corners.csv");
  exportCsv(project, path);
  const auto records = parseCsv(plumb::test::readFile(path));
  ASSERT_EQ(records.size(), 3u);
  EXPECT_EQ(records[0], (std::vector<std::string>{"id", "name", "x", "y", "z", "segment_1", "segment_2", "segment_3",
                                                  "support_1", "support_2", "support_3"}));
  for (std::size_t i = 0; i < project.corners.size(); ++i) {
    const Corner& corner = project.corners[i];
    const std::vector<std::string>& row = records[i + 1];
    ASSERT_EQ(row.size(), 11u);
    EXPECT_EQ(row[0], std::to_string(corner.id));
    EXPECT_EQ(row[1], corner.name);
    // Every digit: the same doubles come back.
    for (Eigen::Index axis = 0; axis < 3; ++axis) {
      EXPECT_EQ(std::stod(row[static_cast<std::size_t>(2 + axis)]), corner.position[axis]);
    }
    for (std::size_t k = 0; k < 3; ++k) {
      EXPECT_EQ(row[5 + k], corner.segments[k] == kNoItem ? "" : std::to_string(corner.segments[k]));
      EXPECT_EQ(std::stod(row[8 + k]), corner.support[k]);
    }
  }
  EXPECT_EQ(records[1][1], "corner \"A\", north");
  EXPECT_EQ(records[2][7], "") << "no third segment";
}

TEST(ExportCsv, AProjectWithoutCornersIsTheHeader) {
  plumb::test::TempDirectory directory;
  const std::string path = directory.file("corners.csv");
  exportCsv(Project{}, path);
  EXPECT_EQ(parseCsv(plumb::test::readFile(path)).size(), 1u);
}

TEST(ExportCsv, MeasurementsWithTheirValuesAndDimensionLines) {
  plumb::test::TempDirectory directory;
  const Project project = test::sampleProject();
  const std::string path = directory.file("measurements.csv");
  exportMeasurementsCsv(project, path);
  const auto records = parseCsv(plumb::test::readFile(path));
  ASSERT_EQ(records.size(), 1u + project.measurements.size());
  EXPECT_EQ(records[0],
            (std::vector<std::string>{"id", "name", "kind", "value", "unit", "perimeter_m", "from_parallel_deg",
                                      "from_x", "from_y", "from_z", "to_x", "to_y", "to_z", "source_1", "source_2"}));
  for (std::size_t i = 0; i < project.measurements.size(); ++i) {
    const Measurement& m = project.measurements[i];
    const MeasureValue value = measure(m.kind, m.terms);
    const std::vector<std::string>& row = records[i + 1];
    ASSERT_EQ(row.size(), 15u);
    EXPECT_EQ(row[0], std::to_string(m.id));
    EXPECT_EQ(row[1], m.name);
    EXPECT_EQ(row[2], measureKindName(m.kind));
    EXPECT_EQ(std::stod(row[3]), value.value) << "every digit";
    EXPECT_EQ(row[4], measureUnit(m.kind));
    EXPECT_EQ(row[5].empty(), m.kind != MeasureKind::kArea);
    EXPECT_EQ(row[6].empty(), m.kind != MeasureKind::kBetweenPlanes);
    for (Eigen::Index axis = 0; axis < 3; ++axis) {
      EXPECT_EQ(std::stod(row[static_cast<std::size_t>(7 + axis)]), value.from[axis]);
      EXPECT_EQ(std::stod(row[static_cast<std::size_t>(10 + axis)]), value.to[axis]);
    }
    for (std::size_t k = 0; k < 2; ++k) {
      const ItemId source = k < m.sources.size() ? m.sources[k] : kNoItem;
      EXPECT_EQ(row[13 + k], source != kNoItem ? std::to_string(source) : "") << "an empty field for none";
    }
  }
  EXPECT_EQ(records[6][2], "area");
  EXPECT_EQ(std::stod(records[6][5]), 5.0) << "the L's perimeter";
  EXPECT_EQ(records[1][13], "30") << "taken from the corner";
}

TEST(ExportCsv, AnInvalidMeasurementIsRefusedAndNothingWritten) {
  plumb::test::TempDirectory directory;
  Project project = test::sampleProject();
  project.measurements[3].terms[1].direction = Eigen::Vector3d::UnitY();  // not parallel any more
  const std::string path = directory.file("measurements.csv");
  try {
    exportMeasurementsCsv(project, path);
    ADD_FAILURE() << "exported";
  } catch (const std::exception& error) {
    EXPECT_NE(std::string(error.what()).find("field 'measurements[3].terms': the planes are 90.00"), std::string::npos)
        << error.what();
  }
  EXPECT_EQ(directory.entryCount(), 0u);
}

}  // namespace
}  // namespace plumb::cad
