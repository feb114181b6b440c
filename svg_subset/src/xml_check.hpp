// svg_subset: the XML well-formedness rules pugixml does not enforce (XML 1.0, 5th edition).
#pragma once

#include <cstddef>
#include <optional>
#include <string>
#include <string_view>

namespace vraster::svg::detail {

/// A violation of XML well-formedness at a byte offset of the text.
struct XmlProblem {
  std::size_t offset;
  std::string message;
};

/// Checks what pugixml accepts but XML forbids, in one linear pass over text that pugixml has already parsed:
/// more than one root element, text or elements after the root (comments, processing instructions and white
/// space are allowed), references to entities that are not predefined (lt, gt, amp, apos, quot) or character
/// references to characters XML does not allow, a bare '&', and '<' inside an attribute value. Entities declared
/// in a DOCTYPE are reported too: they are not expanded. Returns the first problem, or nothing.
std::optional<XmlProblem> find_xml_problem(std::string_view text);

}  // namespace vraster::svg::detail
