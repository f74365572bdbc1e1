#pragma once
// The loader <-> runtime negotiation types of the OpenXR loader's runtime interface ("OpenXR Loader
// - Design and Operation", section "Runtime Interface Negotiation"; the OpenXR 1.0 specification's
// reference pages XrNegotiateLoaderInfo, XrNegotiateRuntimeRequest, XrLoaderInterfaceStructs).
// Debian's OpenXR 1.0.20 headers lack openxr_loader_negotiation.h, so they are declared here with
// the layout and values those pages define; the loader passes them across the C ABI.

#include <cstddef>
#include <cstdint>

#include "tests/support/xr_headset/xr_api.h"

extern "C" {

typedef enum XrLoaderInterfaceStructs {
  XR_LOADER_INTERFACE_STRUCT_UNINTIALIZED = 0,  // sic: the specification's spelling
  XR_LOADER_INTERFACE_STRUCT_LOADER_INFO = 1,
  XR_LOADER_INTERFACE_STRUCT_API_LAYER_REQUEST = 2,
  XR_LOADER_INTERFACE_STRUCT_RUNTIME_REQUEST = 3,
  XR_LOADER_INTERFACE_STRUCT_API_LAYER_CREATE_INFO = 4,
  XR_LOADER_INTERFACE_STRUCT_API_LAYER_NEXT_INFO = 5,
  XR_LOADER_INTERFACE_STRUCTS_MAX_ENUM = 0x7FFFFFFF
} XrLoaderInterfaceStructs;

#define XR_LOADER_INFO_STRUCT_VERSION 1
#define XR_RUNTIME_INFO_STRUCT_VERSION 1
#define XR_CURRENT_LOADER_RUNTIME_VERSION 1

typedef struct XrNegotiateLoaderInfo {
  XrLoaderInterfaceStructs structType;  // XR_LOADER_INTERFACE_STRUCT_LOADER_INFO
  uint32_t structVersion;               // XR_LOADER_INFO_STRUCT_VERSION
  size_t structSize;                    // sizeof(XrNegotiateLoaderInfo)
  uint32_t minInterfaceVersion;
  uint32_t maxInterfaceVersion;
  XrVersion minApiVersion;
  XrVersion maxApiVersion;
} XrNegotiateLoaderInfo;

typedef struct XrNegotiateRuntimeRequest {
  XrLoaderInterfaceStructs structType;            // XR_LOADER_INTERFACE_STRUCT_RUNTIME_REQUEST
  uint32_t structVersion;                         // XR_RUNTIME_INFO_STRUCT_VERSION
  size_t structSize;                              // sizeof(XrNegotiateRuntimeRequest)
  uint32_t runtimeInterfaceVersion;               // written by the runtime
  XrVersion runtimeApiVersion;                    // written by the runtime
  PFN_xrGetInstanceProcAddr getInstanceProcAddr;  // written by the runtime
} XrNegotiateRuntimeRequest;

// The one symbol the runtime library exports: the loader finds it with dlsym.
__attribute__((visibility("default"))) XrResult xrNegotiateLoaderRuntimeInterface(
    const XrNegotiateLoaderInfo* loader_info, XrNegotiateRuntimeRequest* runtime_request);

}  // extern "C"
