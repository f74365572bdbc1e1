#pragma once
// The corners of a project as CSV (RFC 4180: comma separated, CRLF line ends, a field quoted when
// it holds a comma, a double quote, CR or LF, with its double quotes doubled), for spreadsheets
// and survey software. One header line, then one line per corner in the project's order:
//
//   id,name,x,y,z,segment_1,segment_2,segment_3,support_1,support_2,support_3
//
// x, y, z: world coordinates in metres, every digit of the double (cad/number_text.h);
// segment_k: the ids of the three segments, empty for none; support_k: their lambda2, m^2.
//
// The measurements, in the same dialect, one line each in the project's order:
//
//   id,name,kind,value,unit,perimeter_m,from_parallel_deg,from_x,from_y,from_z,to_x,to_y,to_z,source_1,source_2
//
// kind: cad/measurement.h's names (distance, angle, point_to_plane, between_planes, height, area);
// value in unit (m, deg, m2); perimeter_m for an area and from_parallel_deg for two planes, empty
// otherwise; from, to: the dimension line (MeasureValue); source_k: the item each term was taken
// on, empty for none.

#include <string>

#include "cad/project.h"

namespace plumb {
class AtomicFile;
}

namespace plumb::cad {

// Writes the corners of `project` to `out` without committing it. Throws plumb::Error naming
// out.path() when the project breaks a rule of findProjectProblem or the write fails.
void exportCsv(const Project& project, AtomicFile& out);

// Writes them to `path` atomically: on any error nothing appears there. Throws as above.
void exportCsv(const Project& project, const std::string& path);

// The measurements, likewise.
void exportMeasurementsCsv(const Project& project, AtomicFile& out);
void exportMeasurementsCsv(const Project& project, const std::string& path);

}  // namespace plumb::cad
