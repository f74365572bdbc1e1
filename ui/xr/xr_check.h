#pragma once
// OpenXR results as Plumb's errors. A headset problem is an xr::Error: the viewer says it once
// and goes on on the desktop (no runtime, no headset, a lost session), unlike a plumb::Error
// that stops a command.

#include <openxr/openxr.h>

#include <string>

#include "engine/core/error.h"

namespace plumb::xr {

class Error : public plumb::Error {
 public:
  using plumb::Error::Error;
};

// The result's name as the specification spells it, e.g. "XR_ERROR_SESSION_LOST".
std::string resultName(XrResult result);

// `result` unless it failed; throws xr::Error "<what>: <result name>" when it did. Successes
// with a meaning (XR_SESSION_LOSS_PENDING, XR_FRAME_DISCARDED) come back to the caller.
XrResult check(XrResult result, const std::string& what);

// An OpenXR structure of `type`, every other member zero.
template <typename Struct>
Struct xrStruct(XrStructureType type) {
  Struct value{};
  value.type = type;
  return value;
}

}  // namespace plumb::xr
