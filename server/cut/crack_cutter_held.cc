// The ids a CrackCutter still names, for the mesh's reuse of removed ids.
#include "cut/crack_cutter.h"

namespace kerf::cut {
namespace {

using mesh::TetId;
using mesh::VertexId;

void AddEdge(EdgeKey key, absl::flat_hash_set<VertexId>* vertices) {
  for (const VertexId v : EdgeEnds(key)) vertices->insert(v);
}

void AddFace(const FaceKey& key, absl::flat_hash_set<VertexId>* vertices) {
  vertices->insert(key.begin(), key.end());
}

void AddFacePoints(const FacePoints& points, absl::flat_hash_set<VertexId>* vertices) {
  vertices->insert(points.corners.begin(), points.corners.end());
  for (const std::optional<VertexId>& v : points.on_edge) {
    if (v) vertices->insert(*v);
  }
  if (points.inside) vertices->insert(*points.inside);
}

}  // namespace

CrackCutter::HeldIds CrackCutter::Held() const {
  HeldIds held;
  absl::flat_hash_set<VertexId>& v = held.vertices;
  absl::flat_hash_set<TetId>& t = held.tets;
  parting_.AddNamedVertices(&v);
  for (const auto& [key, point] : edge_points_) {
    AddEdge(key, &v);
    v.insert(point.vertex);
  }
  for (const auto& [key, point] : face_points_) {
    AddFace(key, &v);
    v.insert(point.vertex);
  }
  v.insert(on_crack_.begin(), on_crack_.end());
  for (const auto& [key, count] : crack_) AddFace(key, &v);
  for (const FaceKey& key : kept_off_) AddFace(key, &v);
  for (const auto& [key, value] : blade_edges_) AddEdge(key, &v);
  for (const EdgeKey key : advancing_) AddEdge(key, &v);
  for (const auto& [key, vertex] : temporary_) v.insert(vertex);
  for (const MadeVertex& m : made_vertices_) {
    v.insert(m.vertex);
    v.insert(m.from.begin(), m.from.end());
  }
  for (const auto& [vertex, recipe] : recipe_) {
    v.insert(vertex);
    v.insert(recipe.origins.begin(), recipe.origins.end());
  }
  v.insert(new_points_.begin(), new_points_.end());
  for (const auto& [unit, open] : open_) {
    t.insert(unit);
    t.insert(open.source);
    t.insert(open.pieces.begin(), open.pieces.end());
    v.insert(open.corners.begin(), open.corners.end());
    for (const FaceKey& key : open.crack) AddFace(key, &v);
    for (const FaceKey& key : open.openings) AddFace(key, &v);
    for (const FacePoints& points : open.points) AddFacePoints(points, &v);
  }
  t.insert(fresh_.begin(), fresh_.end());
  t.insert(stood_.begin(), stood_.end());
  t.insert(blade_units_.begin(), blade_units_.end());
  for (const auto& [piece, unit] : owner_) t.insert({piece, unit});
  for (const auto& [member, group] : group_of_) t.insert({member, group});
  for (const auto& [group, members] : members_) {
    t.insert(group);
    t.insert(members.begin(), members.end());
  }
  for (const auto& [piece, source] : source_tet_) t.insert({piece, source});
  for (const auto& [source, count] : pieces_of_source_) t.insert(source);
  return held;
}

}  // namespace kerf::cut
