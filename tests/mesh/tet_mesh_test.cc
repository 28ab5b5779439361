#include "mesh/tet_mesh.h"

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <algorithm>
#include <map>
#include <random>
#include <set>

#include "mesh/box_lattice.h"
#include "support/status_message.h"

namespace kerf::mesh {
namespace {

using ::testing::HasSubstr;
using ::testing::UnorderedElementsAre;

TetMesh SingleTet() {
  TetMesh mesh;
  const VertexId a = mesh.AddVertex({0, 0, 0});
  const VertexId b = mesh.AddVertex({1, 0, 0});
  const VertexId c = mesh.AddVertex({0, 1, 0});
  const VertexId d = mesh.AddVertex({0, 0, 1});
  EXPECT_TRUE(mesh.AddTet({a, b, c, d}).ok());
  return mesh;
}

TEST(TetMesh, NewVertexStartsAtRestAndMovesIndependently) {
  TetMesh mesh = SingleTet();
  const VertexId v{1};
  EXPECT_EQ(mesh.current_position(v), mesh.rest_position(v));
  mesh.set_current_position(v, {2, 0, 0});
  EXPECT_EQ(mesh.current_position(v), Eigen::Vector3d(2, 0, 0));
  EXPECT_EQ(mesh.rest_position(v), Eigen::Vector3d(1, 0, 0));
  EXPECT_DOUBLE_EQ(RestVolume(mesh, TetId{0}), 1.0 / 6);
  EXPECT_DOUBLE_EQ(CurrentVolume(mesh, TetId{0}), 2.0 / 6);
}

// A vertex may be added at the position of one already there, passed by reference into the
// mesh itself: the lists it is copied from grow as it is added (the sanitizer build reads
// freed memory if the copy comes too late).
TEST(TetMesh, AVertexAddedAtAnotherVertexsOwnPositionCopiesIt) {
  TetMesh m;
  VertexId last = m.AddVertex({0.1, 0.2, 0.3}, {0.4, 0.5, 0.6});
  for (int k = 0; k < 100; ++k) last = m.AddVertex(m.rest_position(last), m.current_position(last));
  EXPECT_EQ(m.rest_position(last), Eigen::Vector3d(0.1, 0.2, 0.3));
  EXPECT_EQ(m.current_position(last), Eigen::Vector3d(0.4, 0.5, 0.6));
  for (int k = 0; k < 100; ++k) last = m.AddVertex(m.rest_position(last));
  EXPECT_EQ(m.current_position(last), Eigen::Vector3d(0.1, 0.2, 0.3));
}

TEST(TetMesh, IdsAreNotReusedUntilReleased) {
  TetMesh mesh = SingleTet();
  ASSERT_TRUE(mesh.RemoveTet(TetId{0}).ok());
  ASSERT_TRUE(mesh.RemoveVertex(VertexId{3}).ok());
  EXPECT_EQ(mesh.AddVertex({5, 5, 5}), VertexId{4});
  absl::StatusOr<TetId> t = mesh.AddTet({VertexId{0}, VertexId{1}, VertexId{2}, VertexId{4}});
  ASSERT_TRUE(t.ok());
  EXPECT_EQ(*t, TetId{1});
  EXPECT_FALSE(mesh.IsAlive(TetId{0}));
  EXPECT_FALSE(mesh.IsAlive(VertexId{3}));
  EXPECT_EQ(mesh.vertex_count(), 4u);
  EXPECT_EQ(mesh.vertex_index_bound(), 5u);
  EXPECT_EQ(mesh.tet_count(), 1u);
  EXPECT_EQ(std::vector<TetId>(mesh.tets().begin(), mesh.tets().end()), std::vector{TetId{1}});
  EXPECT_EQ(std::vector<VertexId>(mesh.vertices().begin(), mesh.vertices().end()),
            (std::vector{VertexId{0}, VertexId{1}, VertexId{2}, VertexId{4}}));
  EXPECT_EQ(mesh.ids_waiting(), 2u);
}

TEST(TetMesh, RefusesBadRequestsAndChangesNothing) {
  TetMesh mesh = SingleTet();
  const ChangeMark mark = mesh.change_log().Mark();

  absl::Status used = mesh.RemoveVertex(VertexId{0});
  EXPECT_EQ(used.code(), absl::StatusCode::kFailedPrecondition);
  EXPECT_EQ(kerf::testing::StatusMessage(used), "vertex 0 is used by 1 tets");

  absl::StatusOr<TetId> dead = mesh.AddTet({VertexId{0}, VertexId{1}, VertexId{2}, VertexId{9}});
  EXPECT_EQ(dead.status().code(), absl::StatusCode::kInvalidArgument);
  EXPECT_EQ(kerf::testing::StatusMessage(dead), "cannot add a tet on vertex 9: it is not alive");

  EXPECT_EQ(mesh.RemoveTet(TetId{7}).code(), absl::StatusCode::kNotFound);
  EXPECT_THAT(std::string(mesh.RemoveVertex(VertexId{8}).message()), HasSubstr("not alive"));

  EXPECT_EQ(mesh.tet_count(), 1u);
  EXPECT_EQ(mesh.vertex_count(), 4u);
  EXPECT_EQ(mesh.change_log().Mark(), mark);
}

TEST(TetMesh, AdjacencyOfTwoTetsSharingAFace) {
  TetMesh mesh = SingleTet();
  const VertexId e = mesh.AddVertex({1, 1, 1});
  const TetId t1 = *mesh.AddTet({VertexId{1}, VertexId{2}, VertexId{3}, e});
  const TetId t0{0};
  EXPECT_THAT(mesh.TetsAround(VertexId{0}), UnorderedElementsAre(t0));
  EXPECT_THAT(mesh.TetsAround(VertexId{1}), UnorderedElementsAre(t0, t1));
  EXPECT_THAT(mesh.TetsAroundEdge(VertexId{1}, VertexId{2}), UnorderedElementsAre(t0, t1));
  EXPECT_THAT(mesh.TetsAroundEdge(VertexId{0}, VertexId{1}), UnorderedElementsAre(t0));
  EXPECT_THAT(mesh.TetsAroundEdge(VertexId{0}, e), UnorderedElementsAre());
  EXPECT_THAT(mesh.TetsAroundFace(VertexId{3}, VertexId{1}, VertexId{2}),
              UnorderedElementsAre(t0, t1));
  EXPECT_THAT(mesh.TetsAroundFace(VertexId{0}, VertexId{1}, VertexId{2}), UnorderedElementsAre(t0));
}

// Adjacency recomputed from scratch from the live tets.
struct BruteForceAdjacency {
  std::map<VertexId, std::set<TetId>> vertex;
  std::map<std::pair<VertexId, VertexId>, std::set<TetId>> edge;
  std::map<std::array<VertexId, 3>, std::set<TetId>> face;

  explicit BruteForceAdjacency(const TetMesh& mesh) {
    for (const TetId t : mesh.tets()) {
      TetVertices v = mesh.tet(t);
      std::sort(v.begin(), v.end());
      for (int i = 0; i < 4; ++i) {
        vertex[v[i]].insert(t);
        for (int j = i + 1; j < 4; ++j) {
          edge[{v[i], v[j]}].insert(t);
          for (int k = j + 1; k < 4; ++k) face[{v[i], v[j], v[k]}].insert(t);
        }
      }
    }
  }
};

void ExpectAdjacencyMatchesBruteForce(const TetMesh& mesh) {
  const BruteForceAdjacency expected(mesh);
  for (const VertexId v : mesh.vertices()) {
    const auto star = mesh.TetsAround(v);
    const std::set<TetId> actual(star.begin(), star.end());
    ASSERT_EQ(actual.size(), star.size()) << "duplicate in star of " << Index(v);
    const auto it = expected.vertex.find(v);
    ASSERT_EQ(actual, it == expected.vertex.end() ? std::set<TetId>() : it->second)
        << "star of " << Index(v);
  }
  for (const auto& [edge, tets] : expected.edge) {
    const auto around = mesh.TetsAroundEdge(edge.first, edge.second);
    ASSERT_EQ(std::set<TetId>(around.begin(), around.end()), tets);
    ASSERT_EQ(around.size(), tets.size());
  }
  for (const auto& [face, tets] : expected.face) {
    const auto around = mesh.TetsAroundFace(face[2], face[0], face[1]);
    ASSERT_EQ(std::set<TetId>(around.begin(), around.end()), tets);
  }
}

TEST(TetMesh, AdjacencyMatchesBruteForceAfterThousandsOfRandomChanges) {
  BoxLatticeSpec spec;
  spec.cells_x = 4;
  spec.cells_y = 3;
  spec.cells_z = 3;
  TetMesh mesh = *MakeBoxLattice(spec);
  std::mt19937 random(7);
  std::vector<TetVertices> removed;  // tets to put back, so the mesh keeps changing both ways
  // The tets as a reader of the change log sees them, brought up to date now and then; ids are
  // released for reuse (some held) up to what it has read.
  std::map<TetId, TetVertices> seen;
  for (const TetId t : mesh.tets()) seen[t] = mesh.tet(t);
  ChangeMark read = mesh.change_log().Mark();
  constexpr int kOperations = 5000;
  for (int op = 0; op < kOperations; ++op) {
    if (op % 20 == 0) {
      const absl::StatusOr<MeshChanges> changes = mesh.change_log().ChangesSince(read);
      ASSERT_TRUE(changes.ok());
      for (std::size_t i = 0; i < changes->removed_tets.size(); ++i) {
        ASSERT_EQ(seen.at(changes->removed_tets[i]), changes->removed_tet_corners[i]);
        seen.erase(changes->removed_tets[i]);
      }
      for (const TetId t : changes->added_tets) ASSERT_TRUE(seen.emplace(t, mesh.tet(t)).second);
      ASSERT_EQ(seen.size(), mesh.tet_count());
      for (const TetId t : mesh.tets()) ASSERT_EQ(seen.at(t), mesh.tet(t));
      read = mesh.change_log().Mark();
      mesh.ReuseIdsRemovedBefore(
          read, [](VertexId v) { return Index(v) % 5 == 0; },
          [](TetId t) { return Index(t) % 7 == 0; });
    }
    const int kind = static_cast<int>(random() % 4);
    if (kind == 0 && mesh.tet_count() > 0) {
      std::vector<TetId> live(mesh.tets().begin(), mesh.tets().end());
      const TetId t = live[random() % live.size()];
      removed.push_back(mesh.tet(t));
      ASSERT_TRUE(mesh.RemoveTet(t).ok());
    } else if (kind == 1 && !removed.empty()) {
      const std::size_t i = random() % removed.size();
      const TetVertices tet = removed[i];
      removed.erase(removed.begin() + static_cast<std::ptrdiff_t>(i));
      bool all_alive = true;
      for (const VertexId v : tet) all_alive = all_alive && mesh.IsAlive(v);
      if (all_alive) {
        ASSERT_TRUE(mesh.AddTet(tet).ok());
      }
    } else if (kind == 2) {
      // A new vertex and a tet on it and three live vertices of a random live tet.
      std::vector<TetId> live(mesh.tets().begin(), mesh.tets().end());
      if (live.empty()) continue;
      const TetVertices base = mesh.tet(live[random() % live.size()]);
      const VertexId v = mesh.AddVertex(Eigen::Vector3d::Random());
      ASSERT_TRUE(mesh.AddTet({base[0], base[1], base[2], v}).ok());
    } else {
      // Remove a random vertex that nothing uses, if any.
      for (const VertexId v : mesh.vertices()) {
        if (mesh.TetsAround(v).empty()) {
          ASSERT_TRUE(mesh.RemoveVertex(v).ok());
          break;
        }
      }
    }
    if (op % 250 == 0) {
      ExpectAdjacencyMatchesBruteForce(mesh);
    }
  }
  ExpectAdjacencyMatchesBruteForce(mesh);
  std::size_t live_tets = 0;
  for ([[maybe_unused]] const TetId t : mesh.tets()) ++live_tets;
  EXPECT_EQ(live_tets, mesh.tet_count());
  // Ids were reused: the slots are far fewer than the tets ever added.
  EXPECT_LT(mesh.tet_index_bound(), 2 * mesh.tet_count() + 100);
}

TEST(TetMesh, ReleasedIdsAreReusedSmallestFirstButNotHeldOnesNorThoseRemovedAfterTheMark) {
  BoxLatticeSpec spec;  // 6 tets on 8 vertices
  TetMesh mesh = *MakeBoxLattice(spec);
  for (const TetId t : {TetId{4}, TetId{1}, TetId{3}}) ASSERT_TRUE(mesh.RemoveTet(t).ok());
  const ChangeMark mark = mesh.change_log().Mark();
  ASSERT_TRUE(mesh.RemoveTet(TetId{0}).ok());  // after the mark: waits
  const auto none = [](VertexId) { return false; };
  mesh.ReuseIdsRemovedBefore(mark, none, [](TetId t) { return t == TetId{3}; });
  EXPECT_EQ(mesh.ids_free(), 2u);
  EXPECT_EQ(mesh.ids_waiting(), 2u);  // 3, held, and 0, removed after the mark
  const TetVertices corners = {VertexId{0}, VertexId{1}, VertexId{2}, VertexId{7}};
  EXPECT_EQ(*mesh.AddTet(corners), TetId{1});
  EXPECT_EQ(mesh.tet(TetId{1}), corners);
  EXPECT_EQ(*mesh.AddTet(corners), TetId{4});
  EXPECT_EQ(*mesh.AddTet(corners), TetId{6});  // none free: a new slot
  EXPECT_EQ(mesh.tet_index_bound(), 7u);
  EXPECT_EQ(mesh.tet_count(), 5u);
  mesh.ReuseIdsRemovedBefore(mesh.change_log().Mark(), none, [](TetId) { return false; });
  EXPECT_EQ(*mesh.AddTet(corners), TetId{0});
  EXPECT_EQ(*mesh.AddTet(corners), TetId{3});
  for (const TetId t : {TetId{0}, TetId{1}, TetId{3}, TetId{4}}) {
    EXPECT_THAT(mesh.TetsAround(VertexId{7}), ::testing::Contains(t));
  }
  ExpectAdjacencyMatchesBruteForce(mesh);
}

TEST(TetMesh, RepeatedVertexTetIsInThatVertexStarOnce) {
  TetMesh mesh = SingleTet();
  const TetId t = *mesh.AddTet({VertexId{0}, VertexId{0}, VertexId{1}, VertexId{2}});
  const auto star = mesh.TetsAround(VertexId{0});
  EXPECT_EQ(std::count(star.begin(), star.end(), t), 1);
  ASSERT_TRUE(mesh.RemoveTet(t).ok());
  ExpectAdjacencyMatchesBruteForce(mesh);
}

}  // namespace
}  // namespace kerf::mesh
