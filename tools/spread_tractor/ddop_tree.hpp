#pragma once
// A device descriptor object pool (ISO 11783-10 Annex B) as an indented tree for a person: the device,
// then each element under its parent element, each with its process data and properties. Values of
// properties are shown through their value presentation, as a terminal would show them.
#include <string>

#include "isobus/ddop.hpp"

namespace spread::tractor {

std::string describe_ddop_tree(const isobus::Ddop& pool);

}  // namespace spread::tractor
