// CrackCutter: the crack's points in a unit, and the vertices made for them and placed on their
// side of the crack (see crack_cutter.h).
#include <algorithm>

#include "base/check.h"
#include "cut/crack_cutter.h"
#include "cut/fan_triangle.h"

namespace kerf::cut {
namespace {

using mesh::Index;
using mesh::VertexId;

// The middle of three points given by their weights, summed a third at a time.
Eigen::Vector3d MiddleOfThree(const std::array<Eigen::Vector3d, 3>& points) {
  Eigen::Vector3d middle = Eigen::Vector3d::Zero();
  for (const Eigen::Vector3d& p : points) middle += p / 3;
  return middle;
}

}  // namespace

std::array<FacePoints, 4> CrackCutter::PointsOf(const mesh::TetVertices& corners,
                                                const BladeIn* blade) {
  // The blade's point on an edge, if it makes one there.
  const auto blade_fraction = [&](EdgeKey edge) -> std::optional<double> {
    if (blade == nullptr) return std::nullopt;
    const auto at = blade->edges.find(edge);
    return at == blade->edges.end() ? std::nullopt : std::optional<double>(at->second);
  };
  std::array<FacePoints, 4> points;
  for (int k = 0; k < 4; ++k) {
    FacePoints& p = points[k];
    for (int j = 0; j < 3; ++j) p.corners[j] = corners[mesh::kTetFaces[k][j]];
    bool temporary = false;  // a point on its edges is
    for (int j = 0; j < 3; ++j) {
      const VertexId a = p.corners[j], b = p.corners[(j + 1) % 3];
      const EdgeKey edge = MakeEdgeKey(a, b);
      // The blade's point first: where the crack's front advances along an edge with a point,
      // it stands in for that point.
      if (const std::optional<double> at = blade_fraction(edge)) {
        const auto [low, high] = EdgeEnds(edge);
        p.on_edge[j] =
            TemporaryVertex(EdgePlace(edge), {low, high, low, low}, {1 - *at, *at, 0, 0});
        temporary = true;
      } else if (edge_points_.contains(edge)) {
        p.on_edge[j] = EdgePointVertex(a, b);
      }
      p.corner_on_crack[j] = on_crack_.contains(p.corners[j]);
    }
    for (int j = 0; j < 3; ++j) {
      p.edge_on_crack[j] = EdgeOnCrack(p.corners[j], p.corners[(j + 1) % 3]);
    }
    const FaceKey key = MakeFaceKey(p.corners[0], p.corners[1], p.corners[2]);
    if (const auto off = kept_off_in_face_.find(key); off != kept_off_in_face_.end()) {
      p.kept_off = off->second;
    }
    if (face_points_.contains(key)) {
      p.inside = FacePointVertex(key);
      if (blade != nullptr) {
        if (const auto at = blade->beside.find(key); at != blade->beside.end()) {
          PlaceBesidePoint(key, at->second, &p);
        }
      }
    } else if (const auto at =
                   blade ? blade->faces.find(key) : decltype(blade->faces)::const_iterator{};
               blade != nullptr && at != blade->faces.end()) {
      const Eigen::Vector3d& b = at->second;
      p.inside =
          TemporaryVertex(FacePlace(key), {key[0], key[1], key[2], key[0]}, {b[0], b[1], b[2], 0});
    } else if (NeedsHub(p)) {
      // The hub: the middle of the three edge points (weights on the face's vertices in key
      // order), temporary if one of them is; for good, nearer the blade's path where it is off it.
      std::array<Eigen::Vector3d, 3> edge_points;
      for (int j = 0; j < 3; ++j) {
        const VertexId a = p.corners[j], b = p.corners[(j + 1) % 3];
        const EdgeKey edge = MakeEdgeKey(a, b);
        // The blade's point, else the edge's (value_or would look the edge's up either way).
        const std::optional<double> moving = blade_fraction(edge);
        const double fraction = moving ? *moving : edge_points_.at(edge).fraction;
        const auto [low, high] = EdgeEnds(edge);
        edge_points[j] = Eigen::Vector3d::Zero();
        for (int i = 0; i < 3; ++i) {
          if (key[i] == low) edge_points[j][i] += 1 - fraction;
          if (key[i] == high) edge_points[j][i] += fraction;
        }
      }
      if (temporary) {
        const Eigen::Vector3d middle = MiddleOfThree(edge_points);
        p.inside = TemporaryVertex(FacePlace(key), {key[0], key[1], key[2], key[0]},
                                   {middle[0], middle[1], middle[2], 0});
      } else {
        face_points_[key] = {HubNearThePath(key, edge_points)};
        p.inside = FacePointVertex(key);
      }
    }
  }
  return points;
}

Eigen::Vector3d CrackCutter::WeightsOnFace(const FaceKey& key, VertexId v) const {
  Eigen::Vector3d w = Eigen::Vector3d::Zero();
  for (int i = 0; i < 3; ++i) {
    if (key[i] == v) return Eigen::Vector3d::Unit(i);  // a corner (a point the cut made, too)
  }
  const auto recipe = recipe_.find(v);
  KERF_CHECK(recipe != recipe_.end());
  for (int i = 0; i < 3; ++i) {
    for (int k = 0; k < 4; ++k) {
      if (recipe->second.origins[k] == key[i]) w[i] += recipe->second.weights[k];
    }
  }
  return w;
}

void CrackCutter::PlaceBesidePoint(const FaceKey& key, const Eigen::Vector3d& crossing,
                                   FacePoints* p) {
  // The face's boundary from its key's corners on (both tets at the face ask alike).
  std::vector<VertexId> boundary;
  for (int i = 0; i < 3; ++i) {
    boundary.push_back(key[i]);
    const VertexId a = key[i], b = key[(i + 1) % 3];
    for (int j = 0; j < 3; ++j) {
      const VertexId c = p->corners[j], d = p->corners[(j + 1) % 3];
      if (p->on_edge[j] && ((c == a && d == b) || (c == b && d == a))) {
        boundary.push_back(*p->on_edge[j]);
      }
    }
  }
  std::vector<Eigen::Vector3d> weights;
  for (const VertexId v : boundary) weights.push_back(WeightsOnFace(key, v));
  const std::optional<int> holding =
      FanTriangleHolding(weights, WeightsOnFace(key, *p->inside), crossing, kMinTemporaryWeight);
  if (!holding) return;  // at the face's point, or beside the fan's edges: the point's own
  p->beside = TemporaryVertex(FacePlace(key), {key[0], key[1], key[2], key[0]},
                              {crossing[0], crossing[1], crossing[2], 0});
  p->beside_between = {boundary[*holding], boundary[(*holding + 1) % boundary.size()]};
}

VertexId CrackCutter::EdgePointVertex(VertexId a, VertexId b) {
  EdgePoint& e = edge_points_.at(MakeEdgeKey(a, b));
  if (e.vertex == kNoVertex) {
    const VertexId low = Index(a) < Index(b) ? a : b, high = low == a ? b : a;
    e.vertex = MakeVertex({low, high, low, low}, {1 - e.fraction, e.fraction, 0, 0});
  }
  return e.vertex;
}

VertexId CrackCutter::FacePointVertex(const FaceKey& key) {
  FacePoint& f = face_points_.at(key);
  if (f.vertex == kNoVertex) {
    const Eigen::Vector3d& b = f.barycentric;
    f.vertex = MakeVertex({key[0], key[1], key[2], key[0]}, {b[0], b[1], b[2], 0});
  }
  return f.vertex;
}

VertexId CrackCutter::TemporaryVertex(std::uint64_t place, const std::array<VertexId, 4>& origins,
                                      const Eigen::Vector4d& weights) {
  // Placed this pose, and the tets it is placed by the same since.
  const auto [used, first] = temporary_used_.try_emplace(place, edits_);
  const bool placed_as_now = !first && used->second == edits_;
  used->second = edits_;
  const auto it = temporary_.find(place);
  if (it == temporary_.end() || !mesh_->IsAlive(it->second)) {
    return temporary_[place] = MakeVertex(origins, weights);
  }
  PointRecipe& recipe = recipe_[it->second];
  // Each unit at an edge or a face asks for its point: placed once a pose where they agree.
  if (placed_as_now && recipe.origins == origins && recipe.weights == weights) {
    return it->second;
  }
  // The scale reads only the origins the weights use.
  const bool same_origins =
      recipe.origins == origins && ((recipe.weights.array() != 0) == (weights.array() != 0)).all();
  recipe = {origins, weights, same_origins ? recipe.scale : ScaleOf(origins, weights)};
  if (parting_.HasCopies(it->second)) {
    // Parted (a point opening a crack face): its copies lie on the two sides of an opening, so
    // each keeps its own displacement, and the opening stays as open as the tissue made it.
    Eigen::Vector3d rest = Eigen::Vector3d::Zero();
    for (int k = 0; k < 4; ++k) rest += weights[k] * mesh_->rest_position(origins[k]);
    for (const VertexId v : parting_.Ids(it->second)) {
      if (!mesh_->IsAlive(v)) continue;
      const Eigen::Vector3d displacement = mesh_->current_position(v) - mesh_->rest_position(v);
      KERF_CHECK(mesh_->MoveVertex(v, rest, rest + displacement).ok());
    }
  } else {
    for (const VertexId v : parting_.Ids(it->second)) {
      if (mesh_->IsAlive(v)) PlaceOnItsSide(v, origins, weights);
    }
  }
  ++statistics_.moved;
  return it->second;
}

std::optional<std::array<VertexId, 4>> CrackCutter::PlacedAround(
    VertexId v, const std::array<VertexId, 4>& origins, const Eigen::Vector4d& weights) const {
  std::array<bool, 4> found{};
  const std::array<VertexId, 4> named = NamedIn(mesh_->TetsAround(v), origins, &found);
  for (int k = 0; k < 4; ++k) {
    if (weights[k] != 0 && !found[k]) return std::nullopt;
  }
  return named;
}

void CrackCutter::PlaceOnItsSide(VertexId v, const std::array<VertexId, 4>& origins,
                                 const Eigen::Vector4d& weights) {
  const std::optional<std::array<VertexId, 4>> from = PlacedAround(v, origins, weights);
  Eigen::Vector3d rest = Eigen::Vector3d::Zero(), current = Eigen::Vector3d::Zero();
  for (int k = 0; k < 4; ++k) {
    rest += weights[k] * mesh_->rest_position(origins[k]);
    if (from) current += weights[k] * mesh_->current_position((*from)[k]);
  }
  if (!from) current = rest + mesh_->current_position(v) - mesh_->rest_position(v);
  KERF_CHECK(mesh_->MoveVertex(v, rest, current).ok());
  if (from) made_vertices_.push_back({v, *from, weights});
}

VertexId CrackCutter::MakeVertex(const std::array<VertexId, 4>& origins,
                                 const Eigen::Vector4d& weights) {
  // Placed on the origins for now: once parting is done, Repart places it on its own side.
  Eigen::Vector3d rest = Eigen::Vector3d::Zero(), current = Eigen::Vector3d::Zero();
  for (int k = 0; k < 4; ++k) {
    if (weights[k] == 0) continue;
    rest += weights[k] * mesh_->rest_position(origins[k]);
    current += weights[k] * mesh_->current_position(origins[k]);
  }
  const VertexId v = mesh_->AddVertex(rest, current);
  made_vertices_.push_back({v, origins, weights});
  recipe_[v] = {origins, weights, ScaleOf(origins, weights)};
  new_points_.push_back(v);
  return v;
}

Eigen::Vector3d CrackCutter::HubNearThePath(
    const FaceKey& key, const std::array<Eigen::Vector3d, 3>& edge_points) const {
  Eigen::Vector3d middle = MiddleOfThree(edge_points);
  std::optional<std::size_t> first;
  for (const mesh::TetId u : UnitsAround({key[0], key[1], key[2]})) {
    const std::optional<std::size_t> met = FirstPoseIn(u);
    if (met) first = first ? std::min(*first, *met) : *met;
  }
  if (!first || *first < swept_.first()) return middle;
  const double reach = LengthsOf(key).tissue_edge();
  const auto off_path = [&](const Eigen::Vector3d& w) {
    const Eigen::Vector3d x = w[0] * mesh_->current_position(key[0]) +
                              w[1] * mesh_->current_position(key[1]) +
                              w[2] * mesh_->current_position(key[2]);
    double nearest = reach;
    swept_.ForEachStepNear(*first, poses_, x, x, reach, [&](std::size_t i) {
      nearest = std::min(nearest, DistanceToSweep(x, swept_.at(i), swept_.at(i + 1)));
      return true;
    });
    return nearest;
  };
  Eigen::Vector3d best = middle;
  double best_off = off_path(middle);
  if (best_off <= kStepCoverReach * reach) return middle;
  for (const double a : {0.5, 0.7}) {
    for (int j = 0; j < 3; ++j) {
      const Eigen::Vector3d w =
          a * edge_points[j] + (1 - a) / 2 * (edge_points[(j + 1) % 3] + edge_points[(j + 2) % 3]);
      const double off = off_path(w);
      if (off < best_off) best = w, best_off = off;
    }
  }
  return best;
}

double CrackCutter::ScaleOf(const std::array<VertexId, 4>& origins,
                            const Eigen::Vector4d& weights) const {
  std::array<VertexId, 4> used;
  std::size_t n = 0;
  for (int k = 0; k < 4; ++k) {
    if (weights[k] != 0 &&
        std::find(used.begin(), used.begin() + n, origins[k]) == used.begin() + n) {
      used[n++] = origins[k];
    }
  }
  return LengthsOf(std::span<const VertexId>(used.data(), n)).tissue_edge();
}

CrackCutter::Lengths CrackCutter::LengthsOf(std::span<const VertexId> vertices) const {
  Lengths lengths;
  double sum = 0;
  int edges = 0;
  for (std::size_t i = 0; i < vertices.size(); ++i) {
    lengths.scale = std::max(lengths.scale, TissueScale(vertices[i]));
    for (std::size_t j = i + 1; j < vertices.size(); ++j, ++edges) {
      sum += (mesh_->rest_position(vertices[i]) - mesh_->rest_position(vertices[j])).norm();
    }
  }
  if (edges > 0) lengths.mean_edge = sum / edges;
  return lengths;
}

bool CrackCutter::RemovePointIfUnused(VertexId point) {
  if (!parting_.RemoveIfUnused(mesh_, point)) return false;
  recipe_.erase(point);
  return true;
}

}  // namespace kerf::cut
