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
/// references to characters XML does not allow, a bare '&', and '<' inside an attribute value. Run it on the text
/// after expand_internal_entities(): a reference left is one to an undefined entity. Returns the first problem,
/// or nothing.
std::optional<XmlProblem> find_xml_problem(std::string_view text);

/// Limits of entity expansion: a "billion laughs" stops at the first limit it reaches, with an error naming the
/// entity being expanded.
inline constexpr std::size_t kMaxEntities = 10'000;             ///< declarations in the internal subset
inline constexpr int kMaxEntityNesting = 16;                    ///< entities inside entities inside ...
inline constexpr std::size_t kMaxEntityGrowth = std::size_t{1} << 20;  ///< bytes expansion may add (1 MiB)

/// The text with references to the general entities declared in the DOCTYPE's internal subset
/// (<!ENTITY name "value">) replaced by their values, in content and attribute values (not inside comments,
/// CDATA sections or processing instructions), values inside values expanded too; the DOCTYPE itself is kept.
/// External entities (SYSTEM, PUBLIC) and external DTDs are never loaded: a reference to an external entity is
/// an error. `text` is empty when nothing was replaced (use the original); `problem` is set on an error: a
/// limit reached, an entity that refers to itself.
struct EntityExpansion {
  std::string text;
  std::optional<XmlProblem> problem;
};
EntityExpansion expand_internal_entities(std::string_view text);

}  // namespace vraster::svg::detail
