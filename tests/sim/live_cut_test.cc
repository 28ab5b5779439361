// A live progressive cut with a low height guard (few slivers softened): poses are held while
// the blade skims lattice faces, and a held pose drops nothing (the final subdivisions that
// failed with it are tried again), so the whole cut opens.
#include "sim/live_cut.h"

#include <gtest/gtest.h>

#include "absl/strings/str_cat.h"
#include "cut/blade.h"
#include "mesh/io/mesh_file.h"
#include "sim/scene.h"

namespace kerf::sim {
namespace {

TEST(LiveCut, WithALowHeightGuardEveryTetTheBladeCrossesIsCut) {
  const std::string file = absl::StrCat(KERF_SOURCE_DIR, "/server/cut/paths/lattice-straight.json");
  const absl::StatusOr<std::string> text = mesh::ReadTextFile(file);
  ASSERT_TRUE(text.ok()) << text.status();
  const absl::StatusOr<std::vector<cut::BladePose>> path =
      cut::ParseBladePathJson(*text, file, cut::BladeLimits{});
  ASSERT_TRUE(path.ok()) << path.status();
  absl::StatusOr<Scene> scene = LoadScene("lattice-tension");
  ASSERT_TRUE(scene.ok()) << scene.status();
  ASSERT_EQ(scene->method, kerf::v1::Integration::IMPLICIT_EULER);
  scene->min_temporary_height = 0.005;
  const absl::StatusOr<kerf::v1::LiveCutRow> row = RunLiveCut(*std::move(scene), *path, {});
  ASSERT_TRUE(row.ok()) << row.status();
  EXPECT_FALSE(row->blew_up());
  EXPECT_TRUE(row->valid());
  EXPECT_EQ(row->dropped_hits(), 0u);
  EXPECT_EQ(row->cut_tets(), 96u);  // as deferred cutting and the default guard cut
}

}  // namespace
}  // namespace kerf::sim
