// Stable identifiers of mesh elements. An id names one element for as long as it lives, so
// clients can refer to an element across any number of changes; after its removal the id may
// name a new element (see TetMesh).
#pragma once

#include <array>
#include <cstdint>

namespace kerf::mesh {

enum class VertexId : std::uint32_t {};
enum class TetId : std::uint32_t {};

// The dense index behind an id: ids are issued 0, 1, 2, ... (and freed ones again), so this
// indexes per-element arrays.
constexpr std::uint32_t Index(VertexId v) { return static_cast<std::uint32_t>(v); }
constexpr std::uint32_t Index(TetId t) { return static_cast<std::uint32_t>(t); }

// The four corners of a tet. Positive orientation: see geometry::SignedVolume.
using TetVertices = std::array<VertexId, 4>;

// Local vertex indices of the face of a tet opposite corner i, ordered so that the face's
// right-hand normal points out of a positively oriented tet.
inline constexpr std::array<std::array<int, 3>, 4> kTetFaces = {
    {{1, 2, 3}, {0, 3, 2}, {0, 1, 3}, {0, 2, 1}}};

// Local vertex indices of the six edges of a tet.
inline constexpr std::array<std::array<int, 2>, 6> kTetEdges = {
    {{0, 1}, {0, 2}, {0, 3}, {1, 2}, {1, 3}, {2, 3}}};

}  // namespace kerf::mesh
