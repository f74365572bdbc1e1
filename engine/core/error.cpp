#include "engine/core/error.h"

#include <cstring>

namespace plumb {

Error fileError(std::string_view path, std::string_view what) {
  std::string message;
  message.reserve(path.size() + what.size() + 4);
  message.append("'").append(path).append("': ").append(what);
  return Error(message);
}

Error fileErrorAt(std::string_view path, std::uint64_t byte_offset, std::string_view what) {
  std::string message;
  message.append("'").append(path).append("' at byte ").append(std::to_string(byte_offset)).append(": ").append(what);
  return Error(message);
}

std::string systemErrorText(int error_number) {
  // strerror_r has two incompatible signatures; std::strerror is fine for this
  // single-message use and the text is copied out at once.
  return std::strerror(error_number);
}

}  // namespace plumb
