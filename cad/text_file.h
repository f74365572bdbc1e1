#pragma once
// Whole files read into memory, with errors that name them.

#include <string>
#include <string_view>

namespace plumb::cad {

// The bytes of the file at `path`. Throws plumb::Error naming the path when it is a directory or
// cannot be opened or read; `what` says what the file should be ("project file"). Thread-safe.
std::string readTextFile(const std::string& path, std::string_view what);

}  // namespace plumb::cad
