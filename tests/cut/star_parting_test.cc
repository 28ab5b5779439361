#include "cut/star_parting.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <functional>
#include <optional>

#include "absl/container/flat_hash_set.h"
#include "mesh/box_lattice.h"
#include "mesh/connected_components.h"
#include "mesh/mesh_validation.h"

namespace kerf::cut {
namespace {

using mesh::TetMesh;
using mesh::VertexId;

// One cube of six tets around its diagonal from vertex 0 to the far corner.
TetMesh Cube() { return *mesh::MakeBoxLattice({}); }

// The faces of the cube's tets that contain the diagonal, in no order.
std::vector<FaceKey> DiagonalFaces(const TetMesh& m) {
  std::vector<FaceKey> faces;
  for (const mesh::TetId t : m.tets()) {
    const mesh::TetVertices& v = m.tet(t);
    for (const auto& f : mesh::kTetFaces) {
      const FaceKey key = MakeFaceKey(v[f[0]], v[f[1]], v[f[2]]);
      const bool on_diagonal = (m.rest_position(key[0]) - Eigen::Vector3d(0, 0, 0)).norm() == 0 &&
                               m.TetsAroundFace(key[0], key[1], key[2]).size() == 2;
      if (on_diagonal && std::find(faces.begin(), faces.end(), key) == faces.end()) {
        faces.push_back(key);
      }
    }
  }
  return faces;
}

std::vector<VertexId> All(const TetMesh& m) { return {m.vertices().begin(), m.vertices().end()}; }

PartingChanges PartBy(VertexParting* parting, TetMesh* m, const CrackFaceSet& crack) {
  return parting->Repart(m, All(*m), [&](const FaceKey& key) { return crack.contains(key); });
}

// Moves each tet's vertices (current positions) by +0.1 in x if its middle (rest) is `beyond`,
// else by -0.1: the two sides of a parted crack apart.
void OpenApart(TetMesh* m, const std::function<bool(const Eigen::Vector3d&)>& beyond) {
  for (const mesh::TetId t : m->tets()) {
    Eigen::Vector3d middle = Eigen::Vector3d::Zero();
    for (const VertexId v : m->tet(t)) middle += 0.25 * m->rest_position(v);
    for (const VertexId v : m->tet(t)) {
      const Eigen::Vector3d x =
          m->rest_position(v) + Eigen::Vector3d(beyond(middle) ? 0.1 : -0.1, 0, 0);
      ASSERT_TRUE(m->MoveVertex(v, m->rest_position(v), x).ok());
    }
  }
}

TEST(StarParting, NoCrackPartsNothing) {
  TetMesh m = Cube();
  VertexParting parting;
  EXPECT_TRUE(PartBy(&parting, &m, {}).made.empty());
}

TEST(StarParting, ACrackEndingAtAnEdgeLeavesItsVerticesWhole) {
  // One face of the ring around the diagonal: the ring is still joined around the other way, so
  // the diagonal's ends stay whole; the face's third vertex, whose two tets meet only there, is
  // parted.
  TetMesh m = Cube();
  const std::vector<FaceKey> ring = DiagonalFaces(m);
  ASSERT_EQ(ring.size(), 6u);
  VertexParting parting;
  const PartingChanges changes = PartBy(&parting, &m, {ring[0]});
  ASSERT_EQ(changes.made.size(), 1u);
  EXPECT_NE(m.rest_position(changes.made[0].from), Eigen::Vector3d(0, 0, 0));
  EXPECT_NE(m.rest_position(changes.made[0].from), Eigen::Vector3d(1, 1, 1));
  EXPECT_EQ(mesh::FindConnectedComponents(m).count, 1u);
}

TEST(StarParting, ACrackThroughTheBodyPartsItInTwo) {
  // The two faces of the ring in the plane x = y split the cube in two halves.
  TetMesh m = Cube();
  CrackFaceSet crack;
  for (const FaceKey& f : DiagonalFaces(m)) {
    bool in_plane = true;
    for (const VertexId v : f) in_plane &= m.rest_position(v).x() == m.rest_position(v).y();
    if (in_plane) crack.insert(f);
  }
  ASSERT_EQ(crack.size(), 2u);
  const double volume = 1;
  VertexParting parting;
  const PartingChanges changes = PartBy(&parting, &m, crack);
  EXPECT_EQ(changes.made.size(), 4u);  // the plane's four corners
  EXPECT_EQ(mesh::FindConnectedComponents(m).count, 2u);
  EXPECT_TRUE(mesh::FindMeshDefects(m).empty());
  double after = 0;
  for (const mesh::TetId t : m.tets()) after += mesh::RestVolume(m, t);
  EXPECT_NEAR(after, volume, 1e-15);
  for (const VertexCopy& c : changes.made) {
    EXPECT_EQ(m.rest_position(c.copy), m.rest_position(c.from));
    EXPECT_EQ(parting.Origin(c.copy), c.from);
  }
  // The parts are a function of the crack: parting again changes nothing, and without the crack
  // the copies go and the cube is whole again.
  EXPECT_TRUE(PartBy(&parting, &m, crack).replaced.empty());
  const PartingChanges joined = PartBy(&parting, &m, {});
  EXPECT_EQ(joined.removed.size(), 4u);
  EXPECT_EQ(mesh::FindConnectedComponents(m).count, 1u);
  EXPECT_EQ(m.vertex_count(), 8u);
  EXPECT_TRUE(mesh::FindMeshDefects(m).empty());
}

// An opened crack (the two halves moved apart) that parts one half further, so that the other
// half's part becomes the largest at the diagonal's ends: no tet's vertex moves (a part keeps the
// id its tets use), and the origin stays in use.
TEST(StarParting, APartKeepsItsVertexWhenAnotherOutgrowsIt) {
  TetMesh m = Cube();
  CrackFaceSet crack;
  std::vector<FaceKey> others;
  for (const FaceKey& f : DiagonalFaces(m)) {
    bool in_plane = true;
    for (const VertexId v : f) in_plane &= m.rest_position(v).x() == m.rest_position(v).y();
    if (in_plane) {
      crack.insert(f);
    } else {
      others.push_back(f);
    }
  }
  VertexParting parting;
  PartBy(&parting, &m, crack);
  // Open the crack: the half x > y moves by +0.1 in x, the other by -0.1.
  OpenApart(&m, [](const Eigen::Vector3d& middle) { return middle.x() > middle.y(); });
  const auto shape = [&](mesh::TetId t) {
    std::vector<std::pair<std::array<double, 3>, std::array<double, 3>>> corners;
    for (const VertexId v : m.tet(t)) {
      const Eigen::Vector3d& r = m.rest_position(v);
      const Eigen::Vector3d& x = m.current_position(v);
      corners.push_back({{r.x(), r.y(), r.z()}, {x.x(), x.y(), x.z()}});
    }
    std::sort(corners.begin(), corners.end());
    return corners;
  };
  std::vector<decltype(shape(mesh::TetId(0)))> before;
  for (const mesh::TetId t : m.tets()) before.push_back(shape(t));
  // A ring face inside the half that holds the diagonal end's origin.
  const VertexId end = VertexId(0);
  ASSERT_EQ(m.rest_position(end), Eigen::Vector3d(0, 0, 0));
  std::optional<FaceKey> split;
  for (const FaceKey& f : others) {
    const auto around = m.TetsAroundFace(f[0], f[1], f[2]);
    if (around.size() == 2 && mesh::TetHasVertex(m.tet(around[0]), end)) split = f;
  }
  ASSERT_TRUE(split.has_value());
  crack.insert(*split);
  PartBy(&parting, &m, crack);
  EXPECT_TRUE(mesh::FindMeshDefects(m).empty()) << mesh::ValidateMesh(m);
  EXPECT_FALSE(m.TetsAround(end).empty());
  std::vector<decltype(shape(mesh::TetId(0)))> after;
  for (const mesh::TetId t : m.tets()) after.push_back(shape(t));
  std::sort(before.begin(), before.end());
  std::sort(after.begin(), after.end());
  EXPECT_EQ(after, before);
}

// An opened crack, then the tets of the half that holds copies made again by origins (as a split
// makes pieces): named "fresh", they tell nothing of their side, so that half keeps its copies
// and no vertex moves.
TEST(StarParting, TetsMadeByOriginsKeepTheirSidesCopies) {
  {
    // Two cubes side by side, the crack the square between them (x = 1).
    TetMesh m = *mesh::MakeBoxLattice({.cells_x = 2, .size = Eigen::Vector3d(2, 1, 1)});
    CrackFaceSet crack;
    for (const mesh::TetId t : m.tets()) {
      const mesh::TetVertices& v = m.tet(t);
      for (const auto& f : mesh::kTetFaces) {
        const FaceKey key = MakeFaceKey(v[f[0]], v[f[1]], v[f[2]]);
        if (std::all_of(key.begin(), key.end(),
                        [&](VertexId u) { return m.rest_position(u).x() == 1; })) {
          crack.insert(key);
        }
      }
    }
    ASSERT_EQ(crack.size(), 2u);
    VertexParting parting;
    PartBy(&parting, &m, crack);
    // Open it: the half x > 1 moves by +0.1 in x, the other by -0.1.
    OpenApart(&m, [](const Eigen::Vector3d& middle) { return middle.x() > 1; });
    const auto places = [&] {
      std::vector<std::array<double, 6>> corners;
      for (const mesh::TetId t : m.tets()) {
        for (const VertexId v : m.tet(t)) {
          const Eigen::Vector3d& r = m.rest_position(v);
          const Eigen::Vector3d& x = m.current_position(v);
          corners.push_back({r.x(), r.y(), r.z(), x.x(), x.y(), x.z()});
        }
      }
      std::sort(corners.begin(), corners.end());
      return corners;
    };
    const auto before = places();
    // The tets using copies made again by origins, but one for each copy (a side whose tets
    // were all made again has nothing left to tell its copies by).
    absl::flat_hash_set<mesh::TetId> fresh;
    absl::flat_hash_set<VertexId> kept;
    std::vector<mesh::TetId> tets(m.tets().begin(), m.tets().end());
    for (const mesh::TetId t : tets) {
      mesh::TetVertices v = m.tet(t);
      const bool keeps = std::any_of(v.begin(), v.end(), [&](VertexId u) {
        return parting.Origin(u) != u && !kept.contains(u);
      });
      if (keeps) {
        kept.insert(v.begin(), v.end());
        continue;
      }
      if (std::all_of(v.begin(), v.end(), [&](VertexId u) { return parting.Origin(u) == u; })) {
        continue;
      }
      for (VertexId& u : v) u = parting.Origin(u);
      ASSERT_TRUE(m.RemoveTet(t).ok());
      fresh.insert(*m.AddTet(v));
    }
    ASSERT_GE(fresh.size(), 1u);
    parting.Repart(
        &m, All(m), [&](const FaceKey& key) { return crack.contains(key); },
        [&](mesh::TetId t) { return fresh.contains(t); });
    EXPECT_TRUE(mesh::FindMeshDefects(m).empty()) << mesh::ValidateMesh(m);
    EXPECT_EQ(places(), before);
  }
}

}  // namespace
}  // namespace kerf::cut
