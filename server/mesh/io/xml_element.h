// A minimal XML reader for VTK's XML files: elements, attributes and text, no entities,
// CDATA or namespaces. Views point into the parsed text, which must outlive the tree.
#pragma once

#include <optional>
#include <utility>
#include <vector>

#include "absl/status/statusor.h"
#include "absl/strings/string_view.h"

namespace kerf::mesh::internal {

struct XmlElement {
  absl::string_view name;
  std::vector<std::pair<absl::string_view, absl::string_view>> attributes;
  // Everything between the start and end tags of an element with no child elements.
  absl::string_view text;
  std::size_t offset = 0;  // of the start tag in the text
  std::vector<XmlElement> children;

  std::optional<absl::string_view> Attribute(absl::string_view key) const;
  // The first child with this name, or nullptr.
  const XmlElement* Child(absl::string_view child_name) const;
};

// The root element. Errors name the source and line. Nesting deeper than 32 is refused.
absl::StatusOr<XmlElement> ParseXml(absl::string_view text, absl::string_view source);

}  // namespace kerf::mesh::internal
