#include "service/level_view.h"

#include <algorithm>
#include <cstring>

#include "base/check.h"
#include "mesh/boundary_surface.h"
#include "service/sha256.h"

namespace kerf::service {
namespace {

using mesh::Index;
using mesh::TetId;
using mesh::VertexId;

std::array<std::uint32_t, 3> SortedKey(const std::array<std::uint32_t, 3>& v) {
  std::array<std::uint32_t, 3> key = v;
  std::sort(key.begin(), key.end());
  return key;
}

// The same triangle with the same orientation, whichever corner it starts from.
bool SameOrientedTriangle(const std::array<std::uint32_t, 4>& a,
                          const std::array<std::uint32_t, 3>& b) {
  for (int shift = 0; shift < 3; ++shift) {
    if (a[0] == b[shift] && a[1] == b[(shift + 1) % 3] && a[2] == b[(shift + 2) % 3]) return true;
  }
  return false;
}

void SetVector(const Eigen::Vector3d& from, kerf::v1::Vector3* to) {
  to->set_x(from.x());
  to->set_y(from.y());
  to->set_z(from.z());
}

void FillHeader(kerf::v1::Level level, std::uint64_t sequence, std::uint64_t topology_version,
                const TickReport& report, kerf::v1::Frame* frame) {
  frame->set_sequence(sequence);
  frame->set_simulation_time(report.simulation_time);
  frame->set_blade_time(report.blade_time);
  frame->set_send_time_unix_nanos(absl::ToUnixNanos(absl::Now()));
  frame->set_level(level);
  frame->set_topology_version(topology_version);
  SetVector(report.tool_force, frame->mutable_tool_force());
  SetVector(report.tool_torque, frame->mutable_tool_torque());
  if (report.blade) {
    SetVector(report.blade->tip, frame->mutable_blade_tip());
    SetVector(report.blade->heel, frame->mutable_blade_heel());
  }
  *frame->mutable_statistics() = report.statistics;
}

bool MadeByCut(const std::array<std::uint32_t, 3>& v, std::uint32_t original_vertex_bound) {
  return v[0] >= original_vertex_bound && v[1] >= original_vertex_bound &&
         v[2] >= original_vertex_bound;
}

}  // namespace

std::vector<Eigen::Vector3d> ComputeElasticForces(const sim::Simulation& simulation) {
  std::vector<Eigen::Vector3d> f(simulation.state().displacement.size());
  simulation.model().MultiplyStiffness(simulation.state().displacement, f);
  for (Eigen::Vector3d& x : f) x = -x;
  return f;
}

void AppendFloat32(const Eigen::Vector3d& v, std::string* out) {
  static_assert(std::endian::native == std::endian::little, "frames are little-endian");
  const float xyz[3] = {static_cast<float>(v.x()), static_cast<float>(v.y()),
                        static_cast<float>(v.z())};
  out->append(reinterpret_cast<const char*>(xyz), sizeof(xyz));
}

LevelView::LevelView(kerf::v1::Level level, const sim::Simulation& simulation)
    : level_(level),
      simulation_(&simulation),
      original_vertex_bound_(simulation.tissue_vertex_bound()) {}

kerf::v1::Frame LevelView::Advance(const TickReport& report, std::uint64_t sequence) {
  KERF_CHECK(sequence > sequence_);
  kerf::v1::Frame frame;
  switch (level_) {
    case kerf::v1::SURFACE:
      UpdateSurface(&frame);
      break;
    case kerf::v1::VOLUME:
      UpdateTets(&frame);
      UpdateAllVertices(&frame);
      break;
    default:
      UpdateAllVertices(&frame);
      break;
  }
  const bool changed = frame.removed_vertices_size() + frame.added_vertices_size() +
                           frame.removed_elements_size() + frame.added_elements_size() >
                       0;
  if (changed) ++topology_version_;
  synced_ = simulation_->mesh().change_log().Mark();
  sequence_ = sequence;
  last_report_ = report;
  last_report_.nodal_forces = {};
  FillHeader(level_, sequence_, topology_version_, report, &frame);
  FillArrays(report, &frame);
  last_positions_ = frame.positions();
  last_forces_ = frame.nodal_forces();
  return frame;
}

void LevelView::UpdateAllVertices(kerf::v1::Frame* frame) {
  const mesh::TetMesh& m = simulation_->mesh();
  std::vector<std::uint32_t> now;
  now.reserve(m.vertex_count());
  for (const VertexId v : m.vertices()) now.push_back(Index(v));
  std::set_difference(
      vertices_.begin(), vertices_.end(), now.begin(), now.end(),
      google::protobuf::RepeatedFieldBackInserter(frame->mutable_removed_vertices()));
  std::set_difference(now.begin(), now.end(), vertices_.begin(), vertices_.end(),
                      google::protobuf::RepeatedFieldBackInserter(frame->mutable_added_vertices()));
  vertices_ = std::move(now);
}

void LevelView::UpdateTets(kerf::v1::Frame* frame) {
  const mesh::TetMesh& m = simulation_->mesh();
  std::vector<TetId> removed, added;
  absl::StatusOr<mesh::MeshChanges> changes =
      sequence_ != 0 ? m.change_log().ChangesSince(synced_)
                     : absl::StatusOr<mesh::MeshChanges>(absl::OutOfRangeError("first frame"));
  if (changes.ok()) {
    removed = std::move(changes->removed_tets);
    added = std::move(changes->added_tets);
  } else {  // no history to read: compare with the mesh (an id reused has other corners)
    const auto same = [&](const Element& e, TetId t) {
      for (int k = 0; k < 4; ++k) {
        if (e.vertices[k] != Index(m.tet(t)[k])) return false;
      }
      return true;
    };
    for (const auto& [id, element] : elements_) {
      if (!m.IsAlive(TetId{id}) || !same(element, TetId{id})) removed.push_back(TetId{id});
    }
    for (const TetId t : m.tets()) {
      const auto it = elements_.find(Index(t));
      if (it == elements_.end() || !same(it->second, t)) added.push_back(t);
    }
    std::sort(removed.begin(), removed.end());
  }
  for (const TetId t : removed) {
    elements_.erase(Index(t));
    frame->add_removed_elements(Index(t));
  }
  for (const TetId t : added) {
    Element e;
    for (int k = 0; k < 4; ++k) e.vertices[k] = Index(m.tet(t)[k]);
    elements_[Index(t)] = e;
    frame->add_added_elements(Index(t));
    for (const std::uint32_t v : e.vertices) frame->add_added_element_vertices(v);
  }
}

void LevelView::AddTriangle(const FaceKey& key, const std::array<std::uint32_t, 3>& vertices,
                            kerf::v1::Frame* frame) {
  const std::uint32_t id = next_triangle_id_++;
  const bool on_cut = MadeByCut(vertices, original_vertex_bound_);
  elements_[id] = {{vertices[0], vertices[1], vertices[2], 0}, on_cut};
  triangle_of_face_[key] = id;
  frame->add_added_elements(id);
  for (const std::uint32_t v : vertices) {
    frame->add_added_element_vertices(v);
    ++triangles_using_vertex_[v];
  }
  frame->mutable_added_elements_on_cut()->push_back(on_cut ? 1 : 0);
}

void LevelView::RemoveTriangle(const FaceKey& key, kerf::v1::Frame* frame) {
  const auto it = triangle_of_face_.find(key);
  const std::uint32_t id = it->second;
  for (int k = 0; k < 3; ++k) {
    const auto use = triangles_using_vertex_.find(elements_.at(id).vertices[k]);
    if (--use->second == 0) triangles_using_vertex_.erase(use);
  }
  elements_.erase(id);
  triangle_of_face_.erase(it);
  frame->add_removed_elements(id);
}

void LevelView::UpdateSurface(kerf::v1::Frame* frame) {
  const mesh::TetMesh& m = simulation_->mesh();
  // The faces whose state may have changed: those of removed and added tets (all, at first).
  std::vector<std::pair<TetId, int>> faces;
  absl::StatusOr<mesh::MeshChanges> changes =
      sequence_ != 0 ? m.change_log().ChangesSince(synced_)
                     : absl::StatusOr<mesh::MeshChanges>(absl::OutOfRangeError("first frame"));
  std::vector<FaceKey> candidates;
  const auto add_faces_of = [&](const mesh::TetVertices& v) {
    for (const auto& face : mesh::kTetFaces) {
      candidates.push_back(SortedKey({Index(v[face[0]]), Index(v[face[1]]), Index(v[face[2]])}));
    }
  };
  if (changes.ok()) {
    for (const mesh::TetVertices& corners : changes->removed_tet_corners) add_faces_of(corners);
    for (const TetId t : changes->added_tets) add_faces_of(m.tet(t));
  } else {
    for (const auto& [key, id] : triangle_of_face_) candidates.push_back(key);
    for (const TetId t : m.tets()) add_faces_of(m.tet(t));
  }
  std::sort(candidates.begin(), candidates.end());
  candidates.erase(std::unique(candidates.begin(), candidates.end()), candidates.end());
  std::vector<std::uint32_t> touched;  // vertices whose use count may have changed
  for (const FaceKey& key : candidates) {
    // Now a boundary face when exactly one live tet has it; then oriented out of that tet.
    std::optional<std::array<std::uint32_t, 3>> boundary;
    const VertexId a{key[0]}, b{key[1]}, c{key[2]};
    if (key[0] != key[1] && key[1] != key[2] && m.IsAlive(a) && m.IsAlive(b) && m.IsAlive(c)) {
      const auto around = m.TetsAroundFace(a, b, c);
      if (around.size() == 1) {
        const mesh::TetVertices& v = m.tet(around[0]);
        for (const auto& face : mesh::kTetFaces) {
          const std::array<std::uint32_t, 3> tri = {Index(v[face[0]]), Index(v[face[1]]),
                                                    Index(v[face[2]])};
          if (SortedKey(tri) == key) boundary = tri;
        }
      }
    }
    const auto existing = triangle_of_face_.find(key);
    if (existing != triangle_of_face_.end()) {
      const Element& e = elements_.at(existing->second);
      if (boundary && SameOrientedTriangle(e.vertices, *boundary) &&
          e.on_cut == MadeByCut(*boundary, original_vertex_bound_)) {
        continue;
      }
      touched.insert(touched.end(), key.begin(), key.end());
      RemoveTriangle(key, frame);
    }
    if (boundary) {
      touched.insert(touched.end(), key.begin(), key.end());
      AddTriangle(key, *boundary, frame);
    }
  }
  // The vertex set follows the triangles: net additions and removals of the touched vertices.
  std::sort(touched.begin(), touched.end());
  touched.erase(std::unique(touched.begin(), touched.end()), touched.end());
  std::vector<std::uint32_t> added, removed;
  for (const std::uint32_t v : touched) {
    const bool was = std::binary_search(vertices_.begin(), vertices_.end(), v);
    const bool is = triangles_using_vertex_.contains(v);
    if (was && !is) removed.push_back(v);
    if (!was && is) added.push_back(v);
  }
  if (added.empty() && removed.empty()) return;
  std::vector<std::uint32_t> kept;
  std::set_difference(vertices_.begin(), vertices_.end(), removed.begin(), removed.end(),
                      std::back_inserter(kept));
  vertices_.clear();
  std::merge(kept.begin(), kept.end(), added.begin(), added.end(), std::back_inserter(vertices_));
  frame->mutable_removed_vertices()->Add(removed.begin(), removed.end());
  frame->mutable_added_vertices()->Add(added.begin(), added.end());
}

void LevelView::FillArrays(const TickReport& report, kerf::v1::Frame* frame) const {
  const mesh::TetMesh& m = simulation_->mesh();
  if (level_ == kerf::v1::FORCES) {
    KERF_CHECK(report.nodal_forces.size() >= m.vertex_index_bound());
    std::string* out = frame->mutable_nodal_forces();
    out->reserve(12 * vertices_.size());
    for (const std::uint32_t v : vertices_) AppendFloat32(report.nodal_forces[v], out);
    return;
  }
  std::string* out = frame->mutable_positions();
  out->reserve(12 * vertices_.size());
  for (const std::uint32_t v : vertices_) AppendFloat32(m.current_position(VertexId{v}), out);
}

kerf::v1::Frame LevelView::Keyframe() const {
  kerf::v1::Frame frame;
  FillHeader(level_, sequence_, topology_version_, last_report_, &frame);
  frame.set_keyframe(true);
  frame.mutable_added_vertices()->Add(vertices_.begin(), vertices_.end());
  std::vector<std::uint32_t> ids;
  ids.reserve(elements_.size());
  for (const auto& [id, element] : elements_) ids.push_back(id);
  std::sort(ids.begin(), ids.end());
  const int corners = level_ == kerf::v1::VOLUME ? 4 : 3;
  for (const std::uint32_t id : ids) {
    const Element& e = elements_.at(id);
    frame.add_added_elements(id);
    for (int k = 0; k < corners; ++k) frame.add_added_element_vertices(e.vertices[k]);
    if (level_ == kerf::v1::SURFACE) frame.mutable_added_elements_on_cut()->push_back(e.on_cut);
  }
  frame.set_positions(last_positions_);
  frame.set_nodal_forces(last_forces_);
  return frame;
}

std::string ModelSha256(const sim::Simulation& simulation) {
  const mesh::TetMesh& m = simulation.mesh();
  const fem::DynamicState& state = simulation.state();
  std::string bytes;
  const auto put = [&bytes](const auto& value) {
    bytes.append(reinterpret_cast<const char*>(&value), sizeof(value));
  };
  put(state.time);
  for (const VertexId v : m.vertices()) {
    put(Index(v));
    for (const Eigen::Vector3d& x : {m.rest_position(v), m.current_position(v),
                                     state.displacement[Index(v)], state.velocity[Index(v)]}) {
      for (int k = 0; k < 3; ++k) put(x[k]);
    }
  }
  for (const TetId t : m.tets()) {
    put(Index(t));
    for (const VertexId v : m.tet(t)) put(Index(v));
  }
  return Sha256(bytes);
}

kerf::v1::Frame MakeSnapshot(kerf::v1::Level level, const sim::Simulation& simulation,
                             std::uint32_t original_vertex_bound, std::uint64_t sequence,
                             const TickReport& report) {
  const mesh::TetMesh& m = simulation.mesh();
  kerf::v1::Frame frame;
  FillHeader(level, sequence, 0, report, &frame);
  frame.set_keyframe(true);
  std::vector<std::uint32_t> vertices;
  if (level == kerf::v1::SURFACE) {
    std::uint32_t id = 0;
    for (const mesh::BoundaryTriangle& tri : mesh::ExtractBoundarySurface(m)) {
      const std::array<std::uint32_t, 3> v = {Index(tri.vertices[0]), Index(tri.vertices[1]),
                                              Index(tri.vertices[2])};
      frame.add_added_elements(id++);
      frame.mutable_added_element_vertices()->Add(v.begin(), v.end());
      frame.mutable_added_elements_on_cut()->push_back(MadeByCut(v, original_vertex_bound));
      vertices.insert(vertices.end(), v.begin(), v.end());
    }
    std::sort(vertices.begin(), vertices.end());
    vertices.erase(std::unique(vertices.begin(), vertices.end()), vertices.end());
  } else {
    for (const VertexId v : m.vertices()) vertices.push_back(Index(v));
  }
  if (level == kerf::v1::VOLUME) {
    for (const TetId t : m.tets()) {
      frame.add_added_elements(Index(t));
      for (const VertexId v : m.tet(t)) frame.add_added_element_vertices(Index(v));
    }
  }
  frame.mutable_added_vertices()->Add(vertices.begin(), vertices.end());
  if (level == kerf::v1::FORCES) {
    for (const std::uint32_t v : vertices) {
      AppendFloat32(report.nodal_forces[v], frame.mutable_nodal_forces());
    }
  } else {
    for (const std::uint32_t v : vertices) {
      AppendFloat32(m.current_position(VertexId{v}), frame.mutable_positions());
    }
  }
  frame.set_model_sha256(ModelSha256(simulation));
  return frame;
}

}  // namespace kerf::service
