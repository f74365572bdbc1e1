#include "ui/xr/xr_check.h"

#include <openxr/openxr_reflection.h>

namespace plumb::xr {

std::string resultName(XrResult result) {
  switch (result) {
#define PLUMB_XR_RESULT_NAME(name, value) \
  case name:                              \
    return #name;
    XR_LIST_ENUM_XrResult(PLUMB_XR_RESULT_NAME)
#undef PLUMB_XR_RESULT_NAME
            default : return "XrResult " +
                      std::to_string(static_cast<int>(result));
  }
}

XrResult check(XrResult result, const std::string& what) {
  if (XR_FAILED(result)) throw Error(what + ": " + resultName(result));
  return result;
}

}  // namespace plumb::xr
