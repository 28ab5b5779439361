#include "mesh/mesh_change_log.h"

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include "mesh/tet_mesh.h"
#include "support/status_message.h"

namespace kerf::mesh {
namespace {

using ::testing::ElementsAre;
using ::testing::IsEmpty;

TEST(MeshChangeLog, RecordsNetChangesSinceAMark) {
  TetMesh mesh;
  for (int i = 0; i < 4; ++i) mesh.AddVertex(Eigen::Vector3d(i == 1, i == 2, i == 3));
  const ChangeMark start = mesh.change_log().Mark();
  const TetId t0 = *mesh.AddTet({VertexId{0}, VertexId{1}, VertexId{2}, VertexId{3}});
  const VertexId extra = mesh.AddVertex({1, 1, 1});
  const ChangeMark middle = mesh.change_log().Mark();
  const TetId t1 = *mesh.AddTet({VertexId{1}, VertexId{2}, VertexId{3}, extra});
  ASSERT_TRUE(mesh.RemoveTet(t1).ok());  // added and removed within the interval
  ASSERT_TRUE(mesh.RemoveTet(t0).ok());

  absl::StatusOr<MeshChanges> all = mesh.change_log().ChangesSince(start);
  ASSERT_TRUE(all.ok());
  EXPECT_THAT(all->added_vertices, ElementsAre(extra));
  EXPECT_THAT(all->added_tets, IsEmpty());
  EXPECT_THAT(all->removed_tets, IsEmpty());

  absl::StatusOr<MeshChanges> later = mesh.change_log().ChangesSince(middle);
  ASSERT_TRUE(later.ok());
  EXPECT_THAT(later->added_vertices, IsEmpty());
  EXPECT_THAT(later->added_tets, IsEmpty());
  EXPECT_THAT(later->removed_tets, ElementsAre(t0));

  EXPECT_TRUE(mesh.change_log().ChangesSince(mesh.change_log().Mark())->empty());
}

TEST(MeshChangeLog, ReportsVerticesMovedButNotAddedOrRemoved) {
  TetMesh mesh;
  const VertexId a = mesh.AddVertex({0, 0, 0});
  const VertexId b = mesh.AddVertex({1, 0, 0});
  const ChangeMark start = mesh.change_log().Mark();
  ASSERT_TRUE(mesh.MoveVertex(a, {0, 0, 1}, {0, 0, 2}).ok());
  const VertexId c = mesh.AddVertex({2, 0, 0});
  ASSERT_TRUE(mesh.MoveVertex(c, {3, 0, 0}, {3, 0, 0}).ok());  // added: listed as added
  ASSERT_TRUE(mesh.MoveVertex(b, {1, 1, 0}, {1, 1, 0}).ok());
  ASSERT_TRUE(mesh.RemoveVertex(b).ok());  // removed: listed as removed
  EXPECT_EQ(mesh.rest_position(a), Eigen::Vector3d(0, 0, 1));
  EXPECT_EQ(mesh.current_position(a), Eigen::Vector3d(0, 0, 2));

  absl::StatusOr<MeshChanges> changes = mesh.change_log().ChangesSince(start);
  ASSERT_TRUE(changes.ok());
  EXPECT_THAT(changes->moved_vertices, ElementsAre(a));
  EXPECT_THAT(changes->added_vertices, ElementsAre(c));
  EXPECT_THAT(changes->removed_vertices, ElementsAre(b));
  EXPECT_FALSE(changes->empty());
  EXPECT_EQ(mesh.MoveVertex(b, {0, 0, 0}, {0, 0, 0}).code(), absl::StatusCode::kNotFound);
}

// An id removed and given to a new element is both removed (with the corners it had at the mark)
// and added; one added and removed again within the interval, whatever its id did before the
// interval, is only what its life at the two ends says.
TEST(MeshChangeLog, AReusedIdIsRemovedAndAddedWithTheCornersItHadAtTheMark) {
  MeshChangeLog log;
  const TetVertices first = {VertexId{0}, VertexId{1}, VertexId{2}, VertexId{3}};
  const TetVertices second = {VertexId{0}, VertexId{1}, VertexId{2}, VertexId{4}};
  log.RecordAddedTet(TetId{0});
  log.RecordAddedTet(TetId{1});
  const ChangeMark mark = log.Mark();
  log.RecordRemovedTet(TetId{0}, first);
  log.RecordAddedTet(TetId{0});
  log.RecordRemovedTet(TetId{0}, second);
  log.RecordAddedTet(TetId{0});
  log.RecordRemovedTet(TetId{1}, second);  // removed, reused, removed again: only removed
  log.RecordAddedTet(TetId{1});
  log.RecordRemovedTet(TetId{1}, first);
  log.RecordAddedTet(TetId{2});  // added, removed, added: only added
  log.RecordRemovedTet(TetId{2}, first);
  log.RecordAddedTet(TetId{2});
  absl::StatusOr<MeshChanges> changes = log.ChangesSince(mark);
  ASSERT_TRUE(changes.ok());
  EXPECT_THAT(changes->removed_tets, ElementsAre(TetId{0}, TetId{1}));
  EXPECT_THAT(changes->removed_tet_corners, ElementsAre(first, second));
  EXPECT_THAT(changes->added_tets, ElementsAre(TetId{0}, TetId{2}));
}

TEST(MeshChangeLog, DiscardedHistoryIsAnErrorNotAWrongAnswer) {
  MeshChangeLog log;
  log.RecordAddedVertex(VertexId{0});
  const ChangeMark one = log.Mark();
  log.RecordAddedVertex(VertexId{1});
  log.RecordRemovedVertex(VertexId{0});
  log.DiscardBefore(one);
  EXPECT_EQ(log.retained_events(), 2u);

  absl::StatusOr<MeshChanges> since_one = log.ChangesSince(one);
  ASSERT_TRUE(since_one.ok());
  EXPECT_THAT(since_one->added_vertices, ElementsAre(VertexId{1}));
  EXPECT_THAT(since_one->removed_vertices, ElementsAre(VertexId{0}));

  absl::StatusOr<MeshChanges> since_start = log.ChangesSince(ChangeMark{0});
  EXPECT_EQ(since_start.status().code(), absl::StatusCode::kOutOfRange);
  EXPECT_EQ(kerf::testing::StatusMessage(since_start),
            "changes since sequence 0 were discarded (history starts at 1); take a full snapshot");
  EXPECT_EQ(log.ChangesSince(ChangeMark{99}).status().code(), absl::StatusCode::kOutOfRange);
}

}  // namespace
}  // namespace kerf::mesh
