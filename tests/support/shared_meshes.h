// Paths to the real meshes in ../shared/meshes, for tests that skip when it is absent.
#pragma once

#include <filesystem>
#include <string>

namespace kerf::testing {

// The path of a file in shared/meshes, or empty if that folder is not beside the repo.
inline std::string SharedMeshPath(const std::string& name) {
  const std::filesystem::path path = std::filesystem::path(KERF_SHARED_DIR) / "meshes" / name;
  return std::filesystem::exists(path) ? path.string() : std::string();
}

}  // namespace kerf::testing
