#include "cut/face_split.h"

#include <algorithm>
#include <utility>

#include "base/check.h"
#include "cut/element_keys.h"

namespace kerf::cut {
namespace {

using mesh::Index;
using mesh::VertexId;

std::array<VertexId, 2> Segment(VertexId a, VertexId b) {
  return Index(a) < Index(b) ? std::array<VertexId, 2>{a, b} : std::array<VertexId, 2>{b, a};
}

int EdgePointCount(const FacePoints& p) {
  return static_cast<int>(std::count_if(p.on_edge.begin(), p.on_edge.end(),
                                        [](const auto& e) { return e.has_value(); }));
}

// The face's boundary in order: corner 0, the point on edge 0 if any, corner 1, ...
std::vector<VertexId> Boundary(const FacePoints& p) {
  std::vector<VertexId> boundary;
  for (int k = 0; k < 3; ++k) {
    boundary.push_back(p.corners[k]);
    if (p.on_edge[k]) boundary.push_back(*p.on_edge[k]);
  }
  return boundary;
}

// The triangles and the trace (see the header).
FaceSplit SplitFaceTriangles(const FacePoints& p) {
  KERF_CHECK(!(!p.inside && EdgePointCount(p) == 3));
  KERF_CHECK(!p.beside || p.inside);
  FaceSplit split;
  const int edge_points = EdgePointCount(p);
  if (p.inside) {
    const std::vector<VertexId> boundary = Boundary(p);
    for (std::size_t i = 0; i < boundary.size(); ++i) {
      const VertexId b = boundary[i], c = boundary[(i + 1) % boundary.size()];
      if (p.beside && ((b == p.beside_between[0] && c == p.beside_between[1]) ||
                       (b == p.beside_between[1] && c == p.beside_between[0]))) {
        split.triangles.push_back({*p.beside, *p.inside, b});
        split.triangles.push_back({*p.beside, b, c});
        split.triangles.push_back({*p.beside, c, *p.inside});
      } else {
        split.triangles.push_back({*p.inside, b, c});
      }
    }
    if (p.beside) split.trace.push_back(Segment(*p.inside, *p.beside));
    for (int k = 0; k < 3; ++k) {
      if (p.on_edge[k]) split.trace.push_back(Segment(*p.inside, *p.on_edge[k]));
      if (edge_points == 0 && p.corner_on_crack[k]) {
        split.trace.push_back(Segment(*p.inside, p.corners[k]));
      }
    }
    return split;
  }
  if (edge_points == 2) {
    // The corner c between the two cut edges comes off; the quadrilateral (e_in, n, m, e_out)
    // left is split through its vertex of smallest key.
    int c = 0;
    while (!(p.on_edge[c] && p.on_edge[(c + 2) % 3])) ++c;
    const VertexId e_out = *p.on_edge[c], e_in = *p.on_edge[(c + 2) % 3];
    const VertexId n = p.corners[(c + 1) % 3], m = p.corners[(c + 2) % 3];
    split.triangles.push_back({p.corners[c], e_out, e_in});
    if (Index(n) < Index(m)) {
      split.triangles.push_back({e_out, n, e_in});
      split.triangles.push_back({n, m, e_in});
    } else {
      split.triangles.push_back({e_out, n, m});
      split.triangles.push_back({e_out, m, e_in});
    }
    split.trace.push_back(Segment(e_out, e_in));
    return split;
  }
  if (edge_points == 1) {
    int k = 0;
    while (!p.on_edge[k]) ++k;
    const VertexId e = *p.on_edge[k];
    const VertexId a = p.corners[k], b = p.corners[(k + 1) % 3], o = p.corners[(k + 2) % 3];
    split.triangles.push_back({a, e, o});
    split.triangles.push_back({e, b, o});
    for (int j = 0; j < 3; ++j) {
      if (p.corner_on_crack[j]) split.trace.push_back(Segment(e, p.corners[j]));
    }
    return split;
  }
  split.triangles.push_back(p.corners);
  for (int k = 0; k < 3; ++k) {
    if (p.corner_on_crack[k] && p.corner_on_crack[(k + 1) % 3] && p.edge_on_crack[k]) {
      split.trace.push_back(Segment(p.corners[k], p.corners[(k + 1) % 3]));
    }
  }
  return split;
}

}  // namespace

bool NeedsHub(const FacePoints& points) { return !points.inside && EdgePointCount(points) == 3; }

std::vector<VertexId> PointsOnCrack(const FacePoints& p) {
  std::vector<VertexId> on_crack;
  for (int k = 0; k < 3; ++k) {
    if (p.corner_on_crack[k]) on_crack.push_back(p.corners[k]);
    if (p.on_edge[k]) on_crack.push_back(*p.on_edge[k]);
  }
  if (p.inside) on_crack.push_back(*p.inside);
  return on_crack;
}

FaceSplit SplitFace(const FacePoints& p) {
  FaceSplit split = SplitFaceTriangles(p);
  const std::vector<VertexId> on_crack = PointsOnCrack(p);
  const auto kept_off = [&](const std::array<VertexId, 3>& t) {
    return std::any_of(p.kept_off.begin(), p.kept_off.end(), [&](const auto& k) {
      return MakeFaceKey(k[0], k[1], k[2]) == MakeFaceKey(t[0], t[1], t[2]);
    });
  };
  // An edge of the face off the crack though its corners are on it.
  const auto spans_edge_off = [&](const std::array<VertexId, 3>& t) {
    for (int k = 0; k < 3; ++k) {
      if (!p.edge_on_crack[k] && std::find(t.begin(), t.end(), p.corners[k]) != t.end() &&
          std::find(t.begin(), t.end(), p.corners[(k + 1) % 3]) != t.end()) {
        return true;
      }
    }
    return false;
  };
  for (const std::array<VertexId, 3>& t : split.triangles) {
    if (std::all_of(t.begin(), t.end(),
                    [&](VertexId v) {
                      return std::find(on_crack.begin(), on_crack.end(), v) != on_crack.end();
                    }) &&
        !kept_off(t) && !spans_edge_off(t)) {
      split.on_crack.push_back(t);
    }
  }
  return split;
}

}  // namespace kerf::cut
