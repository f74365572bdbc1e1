#include "cad/text_file.h"

#include <cerrno>
#include <filesystem>
#include <fstream>
#include <iterator>

#include "engine/core/error.h"

namespace plumb::cad {

std::string readTextFile(const std::string& path, std::string_view what) {
  std::error_code ignored;
  if (std::filesystem::is_directory(path, ignored)) {
    throw fileError(path, "is a directory, not a " + std::string(what));
  }
  std::ifstream in(path, std::ios::binary);
  if (!in) throw fileError(path, "cannot open the " + std::string(what) + " (" + systemErrorText(errno) + ")");
  std::string text{std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>()};
  if (in.bad()) throw fileError(path, "cannot read the " + std::string(what) + " (" + systemErrorText(errno) + ")");
  return text;
}

}  // namespace plumb::cad
