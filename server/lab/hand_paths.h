// Blade paths as a hand makes them, seeded, for judging a cutter on input nobody designed for
// it (shared/design/cutting.md, "Degenerate blades and real hands").
//
// Every path cuts from above (the tissue's +z): the blade stands along +z from its tip, its heel
// above the tissue, and the tip travels across the tissue's bounding box at a depth into it.
// Poses come at `rate`; positions are the tissue's rest positions.
//   kHand:         a straight pass with tremor (amplitude 0.02-0.2 of the mean edge length, 8-12
//                  Hz, across and along the cut), hesitations every 0.3-0.5 s that back off by
//                  0.1-0.3 of an edge and come again, one reversal of about an edge, and in half
//                  the seeds a withdrawal with the tip inside the tissue (the path ends there).
//   kThroughVertices: the tip passes exactly through mesh vertices, about two edges apart,
//                  near a straight line across (each vertex is the tip of one pose).
//   kAlongEdges:   the tip follows a chain of mesh edges from vertex to vertex.
//   kInFacePlane:  the blade lies in the plane of an interior face and sweeps through it.
#pragma once

#include <cstdint>
#include <string>
#include <vector>

#include "absl/status/statusor.h"
#include "absl/strings/string_view.h"
#include "cut/blade.h"
#include "mesh/tet_mesh.h"

namespace kerf::lab {

enum class PathFamily { kHand, kThroughVertices, kAlongEdges, kInFacePlane };

// "hand", "vertices", "edges", "face-plane"; INVALID_ARGUMENT naming the others.
absl::StatusOr<PathFamily> ParsePathFamily(absl::string_view name);
absl::string_view PathFamilyName(PathFamily family);

struct HandPathOptions {
  double rate = 1000;     // poses per second
  double duration = 1.5;  // s, for kHand: the time the pass would take without pauses
  // Step of the degenerate families' tips, in mean edge lengths per pose.
  double degenerate_step = 0.05;
};

// A path across `tissue` (a non-empty mesh). The same seed gives the same path.
std::vector<cut::BladePose> MakeHandPath(const mesh::TetMesh& tissue, PathFamily family,
                                         std::uint64_t seed, const HandPathOptions& options = {});

// The path as `kerf cut --path` reads it.
std::string FormatBladePathJson(const std::vector<cut::BladePose>& poses);

}  // namespace kerf::lab
