// The scene files of server/sim/scenes/, compiled into kerf (see server/CMakeLists.txt).
#pragma once

#include <array>
#include <utility>

namespace kerf::sim::internal {

extern const std::array<std::pair<const char*, const char*>, 2> kEmbeddedScenes;

}  // namespace kerf::sim::internal
