// Text files compiled into kerf (see kerf_embed_text in server/CMakeLists.txt): the scenes of
// sim/scenes/ and the blade paths of lab/paths/, by file name without extension.
#pragma once

#include <cstddef>
#include <optional>
#include <span>

#include "absl/strings/string_view.h"

namespace kerf {

struct EmbeddedText {
  const char* name;
  const char* text;
};

extern const EmbeddedText kEmbeddedScenes[];
extern const std::size_t kEmbeddedScenes_count;
extern const EmbeddedText kEmbeddedBladePaths[];
extern const std::size_t kEmbeddedBladePaths_count;

inline std::span<const EmbeddedText> EmbeddedScenes() {
  return {kEmbeddedScenes, kEmbeddedScenes_count};
}
inline std::span<const EmbeddedText> EmbeddedBladePaths() {
  return {kEmbeddedBladePaths, kEmbeddedBladePaths_count};
}

// The text of the entry with this name, if any.
inline std::optional<absl::string_view> FindEmbeddedText(std::span<const EmbeddedText> texts,
                                                         absl::string_view name) {
  for (const EmbeddedText& t : texts) {
    if (name == t.name) return absl::string_view(t.text);
  }
  return std::nullopt;
}

}  // namespace kerf
