#pragma once
// The name an exported item goes by: its own, or its kind and id when it has none.

#include <string>
#include <string_view>

#include "cad/project.h"

namespace plumb::cad {

// `name`, or "<kind> <id>" (e.g. "polygon 12") when `name` is empty. The name is returned as
// given: formats with rules for names (OBJ) sanitise it themselves.
std::string itemName(const std::string& name, std::string_view kind, ItemId id);

}  // namespace plumb::cad
