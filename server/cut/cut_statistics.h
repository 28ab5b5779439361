// What a cut did: counts kept by the cutter as it cuts, and the paper's Table 1, the cases of a
// tet the blade is in (progressive cutting).
#pragma once

#include <array>
#include <cstddef>

namespace kerf::cut {

// The paper's Table 1: the case of a tet the blade is in, by its cut edges, its points for good
// on faces (where the tip's path went through), the blade's crossings of its faces (temporary
// points) and whether the tip is inside. Case 8 and 9 have the same counts; in 8 the two cut
// edges share a corner, in 9 they are opposite. 0: none of the eleven (a snapped corner, say).
int ProgressiveCase(int edges, int faces, int temporary_faces, bool tip_inside,
                    bool edges_share_corner);
inline constexpr int kProgressiveCases = 11;

struct CutStatistics {
  std::size_t cut_tets = 0;                   // original tets standing in 2 or more pieces now
  std::size_t new_tets = 0;                   // those pieces
  std::array<std::size_t, 9> tets_by_case{};  // splits for good by CutCase (index = enum value)
  std::size_t snapped_vertices = 0;           // vertices put on the crack by snapping
  std::size_t parted_vertices = 0;            // copies made where the crack parts a vertex
  // Progressive cutting, summed over poses.
  std::array<std::size_t, kProgressiveCases + 1> poses_by_case{};  // tet-poses by Table 1 case
  std::size_t rebuilt = 0;                                         // temporary splits made anew
  std::size_t moved = 0;  // temporary points moved with the blade
};

// What the last pose did (progressive cutting).
struct PoseSummary {
  std::array<std::size_t, kProgressiveCases + 1> tets_by_case{};  // tets the blade is in
  std::size_t open_tets = 0;       // tets split while the blade is in them
  std::size_t temporary_tets = 0;  // the pieces standing in for them now
};

}  // namespace kerf::cut
