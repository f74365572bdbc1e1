#pragma once
// Project files: a Project as JSON ("plumb-project", version 1, usually named *.plumbproj; the
// format is docs/project-file.md). Everything a project holds is written, with numbers that read
// back bit for bit, so a project saved and opened again is the same value.
//
// Both functions are thread-safe as long as no two calls write the same path.

#include <string>

#include "cad/project.h"

namespace plumb::cad {

// The format version this build writes and the newest it reads.
inline constexpr int kProjectFileVersion = 3;  // 2 added "section", 3 "measurements"

// Reads and validates a project file. Throws plumb::Error whose message starts with the quoted
// path and says where (the byte offset for text that is not JSON, otherwise the JSON path of the
// value, e.g. "field 'polygons[2].vertices[1]'") when: the file cannot be read or is empty; it is
// not JSON (truncated, NaN); a key repeats within an object; `format` is not "plumb-project";
// `version` is not a positive whole number or is newer than kProjectFileVersion ("written by a
// newer Plumb"); a required field is missing, a field is unknown or has the wrong type; a number
// is beyond the range of a double; the project breaks a rule of findProjectProblem
// (cad/project_validation.h: ids, references, planes, polygons).
Project readProjectFile(const std::string& path);

// Writes `project` atomically through AtomicFile, every field, so that readProjectFile returns it
// bit for bit (Plane::valid is not written: every segment's plane is valid). Throws plumb::Error
// naming the path when the project breaks a rule of findProjectProblem (naming the place too),
// when a name is not UTF-8, or when the file cannot be written; an existing file at `path` is then
// left as it was.
void writeProjectFile(const Project& project, const std::string& path);

}  // namespace plumb::cad
