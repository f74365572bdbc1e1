#include "cad/item_name.h"

namespace plumb::cad {

std::string itemName(const std::string& name, std::string_view kind, ItemId id) {
  if (!name.empty()) return name;
  return std::string(kind) + " " + std::to_string(id);
}

}  // namespace plumb::cad
