#pragma once
// Errors that happen on users' machines (bad files, full disks, wrong arguments).
// Programmer mistakes are asserts (assert.h); everything a user can cause or fix is a plumb::Error
// whose message says what went wrong, where, and what to do about it.

#include <cstdint>
#include <stdexcept>
#include <string>
#include <string_view>

namespace plumb {

class Error : public std::runtime_error {
 public:
  explicit Error(const std::string& message) : std::runtime_error(message) {}
};

// "<path>: <what>" for errors about a file as a whole (cannot open, cannot rename).
Error fileError(std::string_view path, std::string_view what);

// "<path> at byte <offset>: <what>" for errors at a place inside a file.
Error fileErrorAt(std::string_view path, std::uint64_t byte_offset, std::string_view what);

// The text of errno `error_number`, e.g. "No space left on device".
std::string systemErrorText(int error_number);

}  // namespace plumb
