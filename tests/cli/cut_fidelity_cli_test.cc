// kerf cut's measures of where a cut is against the blade's path, kerf path and the hand-cuts
// experiment, run as a user runs them.
#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <cmath>
#include <fstream>
#include <set>
#include <string>
#include <vector>

#include "absl/strings/str_cat.h"
#include "absl/strings/str_split.h"
#include "cli/kerf_command.h"
#include "google/protobuf/util/json_util.h"
#include "kerf/v1/cut_report.pb.h"
#include "support/run_command.h"

namespace {

using ::testing::HasSubstr;

using CliResult = kerf::testing::CommandResult;
using kerf::testing::Kerf;

// kerf cut measures where the cut is against the path (lab::FidelityMeter) on a mesh at rest:
// the straight path through the paper's lattice is cut where it went; a hand-like path made by
// kerf path is read back and measured too.
TEST(KerfCutFidelity, CutReportsCoverageOfTheSweptSurface) {
  const std::string dir = ::testing::TempDir();
  ASSERT_EQ(Kerf(absl::StrCat("mesh lattice 4 6 4 --size 0.04 0.06 0.04 --out ", dir, "/paper.msh"))
                .exit_code,
            0);
  const auto cut = [&](absl::string_view path, absl::string_view extra) {
    const CliResult run = Kerf(absl::StrCat("cut ", dir, "/paper.msh --path ", path, " --out ", dir,
                                            "/paper-cut.vtu --json", extra));
    EXPECT_EQ(run.exit_code, 0) << run.output;
    kerf::v1::CutReport report;
    EXPECT_TRUE(google::protobuf::util::JsonStringToMessage(run.output, &report).ok());
    return report;
  };
  const kerf::v1::CutReport straight =
      cut(absl::StrCat(KERF_SOURCE_DIR, "/server/lab/paths/lattice-straight.json"), "");
  EXPECT_EQ(straight.check(), "end");
  EXPECT_TRUE(straight.fidelity_measured());
  EXPECT_EQ(straight.crossed_tets(), 96u);  // a cross-section of the lattice
  EXPECT_GE(straight.swept_samples(), 20 * straight.crossed_tets());
  EXPECT_EQ(straight.coverage(), 1);
  EXPECT_EQ(straight.overcut_faces(), 0u);
  EXPECT_EQ(straight.unpaired_crack_faces(), 0u);
  EXPECT_GT(straight.crack_faces(), 0u);
  const CliResult path = Kerf(absl::StrCat(
      "path hand ", dir, "/paper.msh --seed 3 --duration 0.3 --out ", dir, "/hand.json"));
  ASSERT_EQ(path.exit_code, 0) << path.output;
  EXPECT_THAT(path.output, HasSubstr("hand path, seed 3: "));
  const kerf::v1::CutReport hand =
      cut(dir + "/hand.json", absl::StrCat(" --check every --deferred --uncovered ", dir,
                                           "/uncovered.csv --overcut ", dir, "/overcut.csv"));
  // One row per sample no crack face covers, and per overcut face, under a header.
  const auto rows = [](const std::string& file) {
    std::ifstream in(file);
    std::string line;
    int n = -1;
    while (std::getline(in, line)) ++n;
    return n;
  };
  EXPECT_EQ(rows(dir + "/uncovered.csv"),
            std::lround((1 - hand.coverage()) * hand.swept_samples()));
  EXPECT_EQ(rows(dir + "/overcut.csv"), static_cast<int>(hand.overcut_faces()));
  EXPECT_EQ(hand.check(), "every");
  EXPECT_GT(hand.swept_samples(), 0u);
  EXPECT_GT(hand.coverage(), 0);
  EXPECT_LE(hand.coverage(), 1);
  EXPECT_LE(hand.min_step_coverage(), 1);
  // Deferred, the crack waits for the blade to leave a tet: steps lag, below the surface too.
  EXPECT_GT(hand.poses_not_covered_below_surface(), 0u);
  EXPECT_LE(hand.poses_not_covered_below_surface(), hand.poses_not_covered());
  // --lagging: a row for each sample of each pose's own step left uncovered after that pose, so
  // at least one for each pose lagging, below the surface among them.
  const kerf::v1::CutReport lagging =
      cut(dir + "/hand.json", absl::StrCat(" --deferred --lagging ", dir, "/lagging.csv"));
  EXPECT_EQ(lagging.check(), "every");
  EXPECT_EQ(lagging.poses_not_covered(), hand.poses_not_covered());
  std::ifstream lag(dir + "/lagging.csv");
  std::string line;
  ASSERT_TRUE(std::getline(lag, line));
  EXPECT_EQ(line, "pose,x,y,z,edge,tissue_tet,below_surface");
  std::set<int> poses_lagging, below_surface;
  while (std::getline(lag, line)) {
    const std::vector<std::string> cells = absl::StrSplit(line, ',');
    ASSERT_EQ(cells.size(), 7u) << line;
    poses_lagging.insert(std::stoi(cells[0]));
    if (cells[6] == "1") below_surface.insert(std::stoi(cells[0]));
  }
  EXPECT_EQ(poses_lagging.size(), hand.poses_not_covered());
  EXPECT_EQ(below_surface.size(), hand.poses_not_covered_below_surface());
  EXPECT_THAT(Kerf(absl::StrCat("cut ", dir, "/paper.msh --path ", dir, "/hand.json --out ", dir,
                                "/x.vtu --check end --lagging ", dir, "/x.csv"))
                  .output,
              HasSubstr("--lagging is of every pose: it needs --check every"));
  // Progressively (the default) the cut is where the hand went, valid after every pose.
  const kerf::v1::CutReport progressive = cut(dir + "/hand.json", " --check every");
  EXPECT_EQ(progressive.mode(), "progressive");
  EXPECT_EQ(progressive.invalid_poses(), 0u);
  EXPECT_GE(progressive.coverage(), 0.97);
  EXPECT_EQ(progressive.overcut_faces(), 0u);
  EXPECT_THAT(Kerf(absl::StrCat("cut ", dir, "/paper.msh --path ", dir, "/hand.json --out ", dir,
                                "/x.vtu --check sometimes"))
                  .output,
              HasSubstr("--check takes every or end, not \"sometimes\""));
  EXPECT_THAT(Kerf(absl::StrCat("path wobble ", dir, "/paper.msh --out ", dir, "/x.json")).output,
              HasSubstr("unknown path family \"wobble\""));
}

// The hand-cuts experiment cuts every family in both modes; the cuts cover the swept surface and
// are valid at the end.
TEST(KerfCutFidelity, HandCutsExperimentCutsEveryFamilyInBothModes) {
  const CliResult run = Kerf("experiment hand-cuts --seeds 1 --json");
  ASSERT_EQ(run.exit_code, 0) << run.output;
  kerf::v1::CutExperiment experiment;
  ASSERT_TRUE(google::protobuf::util::JsonStringToMessage(run.output, &experiment).ok());
  EXPECT_EQ(experiment.cuts_size(), 4 * 2);  // families x modes
  for (const kerf::v1::CutReport& r : experiment.cuts()) {
    EXPECT_GE(r.coverage(), 0.85) << r.path() << " " << r.mode();
    EXPECT_EQ(r.invalid_poses(), 0u) << r.path();
    EXPECT_TRUE(r.valid()) << r.path();
  }
  EXPECT_THAT(Kerf("experiment hand-cuts --seeds 0").output, HasSubstr("at least 1"));
}

}  // namespace
