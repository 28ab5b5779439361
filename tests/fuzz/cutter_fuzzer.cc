// Fuzz target for the cutter: the input steers a blade through a small bar (each 7 bytes:
// tip and heel moves, and a byte that may hesitate or withdraw the blade); an odd length cuts
// progressively, an even one deferred. Whatever the blade does, after every pose the mesh is
// valid and conforming and keeps its volume.
#include <cstddef>
#include <cstdint>
#include <cstdlib>

#include "cut/crack_cutter.h"
#include "mesh/box_lattice.h"
#include "mesh/mesh_validation.h"

namespace {

double Volume(const kerf::mesh::TetMesh& m) {
  double v = 0;
  for (const kerf::mesh::TetId t : m.tets()) v += kerf::mesh::RestVolume(m, t);
  return v;
}

void Check(const kerf::mesh::TetMesh& m, double volume) {
  if (!kerf::mesh::FindMeshDefects(m).empty()) std::abort();
  if (std::abs(Volume(m) - volume) > 1e-12 * volume) std::abort();
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* bytes, std::size_t size) {
  kerf::mesh::BoxLatticeSpec spec;
  spec.cells_x = 3;
  spec.cells_y = 2;
  spec.cells_z = 2;
  spec.size = {0.03, 0.02, 0.02};
  kerf::mesh::TetMesh m = *kerf::mesh::MakeBoxLattice(spec);
  const double volume = Volume(m);
  kerf::cut::BladeLimits limits;
  limits.max_speed = 1e9;
  kerf::cut::CrackCutter cutter = *kerf::cut::CrackCutter::Create(
      &m, 0.01, limits,
      {.mode = size % 2 == 1 ? kerf::cut::CutMode::kProgressive : kerf::cut::CutMode::kDeferred});
  Eigen::Vector3d tip(0.015, -0.003, 0.005), heel(0.015, -0.003, 0.03);
  double time = 0;
  for (std::size_t i = 0; i + 7 <= size; i += 7) {
    const auto move = [&](std::size_t k) { return static_cast<std::int8_t>(bytes[i + k]) * 2e-5; };
    tip += Eigen::Vector3d(move(0), move(1), move(2));
    heel += Eigen::Vector3d(move(3), move(4), move(5));
    if (bytes[i + 6] == 0xff) {
      cutter.Finish();
    } else if (!cutter.ApplyPose({time, tip, heel}).ok()) {
      return 0;  // a refused pose changes nothing; the path ends here
    }
    time += 0.001;
    Check(m, volume);
  }
  cutter.Finish();
  Check(m, volume);
  return 0;
}
