// LevelView: the frames a subscriber rebuilds the view from, while a cut removes tets and the
// mesh gives their ids to new ones.
#include "service/level_view.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <map>
#include <set>
#include <vector>

#include "sim/blade_messages.h"
#include "sim/scene.h"
#include "support/service_bar.h"

namespace kerf::service {
namespace {

// What a subscriber keeps (see frame.proto): the vertex set and the elements by id.
struct Rebuilt {
  std::set<std::uint32_t> vertices;
  std::map<std::uint32_t, std::vector<std::uint32_t>> elements;
  std::size_t ids_added_again = 0;  // element ids a frame removed and added

  void Apply(const kerf::v1::Frame& f) {
    if (f.keyframe()) *this = {};
    for (const std::uint32_t v : f.removed_vertices()) ASSERT_EQ(vertices.erase(v), 1u);
    for (const std::uint32_t v : f.added_vertices()) ASSERT_TRUE(vertices.insert(v).second);
    const std::set<std::uint32_t> removed(f.removed_elements().begin(), f.removed_elements().end());
    for (const std::uint32_t e : removed) ASSERT_EQ(elements.erase(e), 1u);
    const int corners = f.level() == kerf::v1::VOLUME ? 4 : 3;
    for (int i = 0; i < f.added_elements_size(); ++i) {
      ids_added_again += removed.contains(f.added_elements(i));
      const auto first = f.added_element_vertices().begin() + corners * i;
      ASSERT_TRUE(
          elements.emplace(f.added_elements(i), std::vector(first, first + corners)).second);
    }
  }
  // Triangles (or tets) as sorted corner lists: a SURFACE view's element ids are its own.
  std::multiset<std::vector<std::uint32_t>> Shapes() const {
    std::multiset<std::vector<std::uint32_t>> shapes;
    for (auto [id, corners] : elements) {
      std::sort(corners.begin(), corners.end());
      shapes.insert(corners);
    }
    return shapes;
  }
};

TEST(LevelView, FramesRebuildTheViewWhileACutReusesIds) {
  absl::StatusOr<sim::Scene> scene =
      sim::BuildScene(*sim::ParseSceneText(kerf::testing::kServiceBarScene, "test"), ".");
  ASSERT_TRUE(scene.ok()) << scene.status();
  scene->conditions = {};
  absl::StatusOr<std::unique_ptr<sim::Simulation>> simulation =
      sim::Simulation::Create(*std::move(scene));
  ASSERT_TRUE(simulation.ok()) << simulation.status();
  sim::Simulation& s = **simulation;
  const kerf::v1::Level levels[] = {kerf::v1::SURFACE, kerf::v1::VOLUME};
  std::vector<LevelView> views;
  std::vector<Rebuilt> rebuilt(2);
  for (const kerf::v1::Level level : levels) views.emplace_back(level, s);
  const TickReport report;
  std::uint64_t sequence = 0;
  // A blade trembling 1 mm at 10 Hz across the bar for 4 s at 200 poses a second; the views
  // take a frame every 7 poses, and the mesh's log is kept for them, as a session does.
  for (int k = 0; k <= 800; ++k) {
    const double t = k / 200.0;
    const double x = 0.008 + 0.004 * t / 4 + 0.001 * std::sin(2 * M_PI * 10 * t);
    absl::StatusOr<cut::BladePose> pose =
        sim::BladePoseFromProto(kerf::testing::BarBladePose(t, 0.0103, x));
    ASSERT_TRUE(pose.ok()) << pose.status();
    ASSERT_TRUE(s.ApplyBladePose(*pose).ok()) << "pose " << k;
    s.Step();
    if (k % 7 == 0) {
      ++sequence;
      for (int l = 0; l < 2; ++l) rebuilt[l].Apply(views[l].Advance(report, sequence));
    }
    mesh::ChangeMark keep = views[0].synced();
    if (views[1].synced().sequence < keep.sequence) keep = views[1].synced();
    s.DiscardChangesBefore(keep);
  }
  ++sequence;
  for (int l = 0; l < 2; ++l) {
    rebuilt[l].Apply(views[l].Advance(report, sequence));
    Rebuilt fresh;
    fresh.Apply(LevelView(levels[l], s).Advance(report, 1));  // everything, from the mesh
    EXPECT_EQ(rebuilt[l].vertices, fresh.vertices) << levels[l];
    EXPECT_EQ(rebuilt[l].Shapes(), fresh.Shapes()) << levels[l];
    if (levels[l] == kerf::v1::VOLUME) {
      EXPECT_EQ(rebuilt[l].elements, fresh.elements);
    }
  }
  // The cut churned: tets ids were given to new tets, and a frame said so.
  EXPECT_GT(rebuilt[1].ids_added_again, 0u);
  EXPECT_LT(s.mesh().tet_index_bound(), s.mesh().tet_count() + 2 * sim::Simulation::kIdReuseBatch);
}

}  // namespace
}  // namespace kerf::service
