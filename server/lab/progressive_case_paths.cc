#include "lab/progressive_case_paths.h"

#include <algorithm>
#include <cmath>

#include "mesh/box_lattice.h"

namespace kerf::lab {
namespace {

// Appends poses moving the blade by `tip_travel` and `heel_travel` in steps of at most 1 mm.
void Move(std::vector<cut::BladePose>* poses, const Eigen::Vector3d& tip_travel,
          const Eigen::Vector3d& heel_travel) {
  const cut::BladePose from = poses->back();
  const int steps = std::max(
      1, static_cast<int>(std::ceil(std::max(tip_travel.norm(), heel_travel.norm()) / 0.001)));
  for (int k = 1; k <= steps; ++k) {
    const double f = static_cast<double>(k) / steps;
    poses->push_back(
        {from.time + 0.01 * k, from.tip + f * tip_travel, from.heel + f * heel_travel});
  }
}

void Hold(std::vector<cut::BladePose>* poses, int count) {
  for (int k = 0; k < count; ++k) {
    cut::BladePose pose = poses->back();
    pose.time += 0.01;
    poses->push_back(pose);
  }
}

std::vector<cut::BladePose> Start(const Eigen::Vector3d& tip, const Eigen::Vector3d& heel) {
  return {{0, tip, heel}};
}

}  // namespace

mesh::TetMesh ScriptedPathLattice() {
  return *mesh::MakeBoxLattice(
      {.cells_x = 6, .cells_y = 2, .cells_z = 2, .size = {0.06, 0.02, 0.02}});
}

std::vector<ScriptedPath> ProgressiveCasePaths() {
  std::vector<ScriptedPath> paths;
  const Eigen::Vector3d y(0, 1, 0), z(0, 0, 1);
  {
    // Through the whole depth, across the bar: the blade edge crosses two faces of each tet.
    std::vector<cut::BladePose> p = Start({0.0337, -0.005, -0.005}, {0.0337, -0.005, 0.025});
    Move(&p, 0.03 * y, 0.03 * y);
    paths.push_back({"through", "through the whole depth, across the bar", p, {3, 6, 10}});
  }
  {
    // The tip 9.3 mm deep, across the bar: the tip is inside the tets it cuts.
    std::vector<cut::BladePose> p = Start({0.0337, -0.005, 0.0107}, {0.0337, -0.005, 0.03});
    Move(&p, 0.03 * y, 0.03 * y);
    paths.push_back({"tip-inside", "the tip 9.3 mm deep, across the bar", p, {4}});
  }
  {
    // Plunging straight down into the bar, then across: the tip enters a tet through the face
    // the blade crosses (case 1), then passes through it into the tet below (case 2).
    std::vector<cut::BladePose> p = Start({0.0337, 0.0063, 0.025}, {0.0337, 0.0063, 0.045});
    Move(&p, -0.0203 * z, -0.0203 * z);
    Move(&p, 0.008 * y, 0.008 * y);
    paths.push_back({"plunge", "straight down into the bar, then across", p, {1, 2}});
  }
  // Tilted blades entering the side y = 0 and running across the bar, each moving its tip
  // and heel along straight lines (0.7 mm per pose) for 40 poses; found by a search over
  // random blades for the cases the others do not reach.
  const struct {
    const char* name;
    Eigen::Vector3d tip, heel, tip_step, heel_step;
    std::vector<int> cases;
  } tilted[] = {
      {"tilted-a",
       {0.0433, -0.0040, 0.0029},
       {0.0475, -0.0064, 0.0325},
       {-0.000028, 0.000679, -0.000167},
       {0.000070, 0.000676, -0.000196},
       {5, 9, 10}},
      {"tilted-b",
       {0.0360, -0.0040, 0.0149},
       {0.0337, 0.0016, 0.0443},
       {-0.000106, 0.000683, 0.000108},
       {-0.000031, 0.000607, 0.000049},
       {4, 7}},
      {"tilted-c",
       {0.0126, -0.0040, 0.0113},
       {0.0112, -0.0097, 0.0407},
       {-0.000084, 0.000693, 0.000045},
       {-0.000122, 0.000780, -0.000030},
       {8}},
      {"tilted-d",
       {0.0268, -0.0040, 0.0077},
       {0.0239, 0.0038, 0.0365},
       {0.000023, 0.000686, 0.000137},
       {0.000070, 0.000710, 0.000166},
       {11}},
  };
  for (const auto& t : tilted) {
    std::vector<cut::BladePose> p = Start(t.tip, t.heel);
    for (int k = 0; k < 40; ++k) Move(&p, t.tip_step, t.heel_step);
    paths.push_back({t.name, "tilted, across the bar", p, t.cases});
  }
  {
    // The tip inside: it stops in the middle of a tet, hesitates, turns back half way, goes on
    // again and stops inside; the path ends there (the blade is withdrawn inside the tets).
    std::vector<cut::BladePose> p = Start({0.0237, -0.005, 0.0127}, {0.0237, -0.005, 0.03});
    Move(&p, 0.0105 * y, 0.0105 * y);
    Hold(&p, 5);
    Move(&p, -0.004 * y, -0.004 * y);
    Move(&p, 0.0063 * y, 0.0063 * y);
    Hold(&p, 3);
    paths.push_back({"stop-turn-withdraw",
                     "the tip inside: stops, turns back, goes on, withdrawn inside",
                     p,
                     {4}});
  }
  {
    // Through the whole depth, tilting as it goes (the heel moves further than the tip), with
    // a tremble across the cut.
    std::vector<cut::BladePose> p = Start({0.0137, -0.005, -0.005}, {0.0117, -0.005, 0.025});
    for (int k = 0; k < 6; ++k) {
      Move(&p, Eigen::Vector3d(0.0007, 0.005, 0), Eigen::Vector3d(0.0017, 0.005, 0));
      Move(&p, Eigen::Vector3d(-0.0004, 0, 0), Eigen::Vector3d(-0.0004, 0, 0));
    }
    paths.push_back(
        {"tilting-tremble", "through the depth, tilting, trembling across", p, {3, 6, 10}});
  }
  return paths;
}

}  // namespace kerf::lab
