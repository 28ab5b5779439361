#include "cut/cut_statistics.h"

namespace kerf::cut {

int ProgressiveCase(int edges, int faces, int temporary_faces, bool tip_inside,
                    bool edges_share_corner) {
  struct Row {
    int edges, faces, temporary_faces;
    bool tip_inside;
  };
  static constexpr std::array<Row, kProgressiveCases> kTable = {{{0, 1, 1, true},
                                                                 {0, 2, 2, false},
                                                                 {1, 0, 2, false},
                                                                 {1, 1, 1, true},
                                                                 {1, 2, 2, false},
                                                                 {2, 0, 2, false},
                                                                 {2, 1, 1, true},
                                                                 {2, 2, 2, false},
                                                                 {2, 2, 2, false},
                                                                 {3, 0, 2, false},
                                                                 {3, 1, 1, true}}};
  for (int k = 0; k < kProgressiveCases; ++k) {
    const Row& row = kTable[k];
    if (row.edges != edges || row.faces != faces || row.temporary_faces != temporary_faces ||
        row.tip_inside != tip_inside) {
      continue;
    }
    if (k == 7 && !edges_share_corner) continue;  // case 8: the cut edges share a corner
    return k + 1;
  }
  return 0;
}

}  // namespace kerf::cut
