#include "cli/experiments/calculix_reference.h"

#include <array>
#include <fstream>
#include <sstream>

#include "absl/container/flat_hash_map.h"
#include "absl/strings/match.h"
#include "absl/strings/str_cat.h"
#include "absl/strings/str_format.h"
#include "cli/external_program.h"

namespace kerf::cli {
namespace {

// ccx reads at most about 20 characters a number: 12 significant digits.
std::string Coordinates(const Eigen::Vector3d& p) {
  return absl::StrFormat("%.12g, %.12g, %.12g", p.x(), p.y(), p.z());
}

// The deck: the lattice's vertices (node = index + 1) and a node in the middle of each edge,
// C3D10 elements (corners, then the middles of edges 12, 23, 13, 14, 24, 34), the held faces
// and the load, and the quantity printed.
absl::StatusOr<std::string> Deck(lab::BarLoad load, int n) {
  absl::StatusOr<sim::Scene> scene = lab::MakeBarScene(
      load, n, kerf::v1::Integration::STATIC, fem::ElasticLaw::kLinear, /*mass_damping=*/0);
  if (!scene.ok()) return scene.status();
  const mesh::TetMesh& m = scene->mesh;
  std::vector<Eigen::Vector3d> nodes;  // by node id - 1
  for (std::uint32_t i = 0; i < m.vertex_index_bound(); ++i) {
    nodes.push_back(m.rest_position(mesh::VertexId{i}));
  }
  absl::flat_hash_map<std::pair<std::uint32_t, std::uint32_t>, std::size_t> middles;
  std::string elements = "*ELEMENT, TYPE=C3D10, ELSET=EALL\n";
  int element = 0;
  constexpr std::array<std::array<int, 2>, 6> kEdges = {
      {{0, 1}, {1, 2}, {0, 2}, {0, 3}, {1, 3}, {2, 3}}};
  for (const mesh::TetId t : m.tets()) {
    const mesh::TetVertices& v = m.tet(t);
    absl::StrAppend(&elements, ++element);
    for (const mesh::VertexId corner : v) absl::StrAppend(&elements, ", ", mesh::Index(corner) + 1);
    for (const auto& [a, b] : kEdges) {
      const std::uint32_t i = mesh::Index(v[a]), j = mesh::Index(v[b]);
      const std::pair<std::uint32_t, std::uint32_t> key(std::min(i, j), std::max(i, j));
      auto [it, added] = middles.try_emplace(key, nodes.size());
      if (added) nodes.push_back((m.rest_position(v[a]) + m.rest_position(v[b])) / 2);
      absl::StrAppend(&elements, ", ", it->second + 1);
    }
    absl::StrAppend(&elements, "\n");
  }
  std::string deck = "*HEADING\nkerf accuracy bar\n*NODE, NSET=NALL\n";
  std::string held, pulled, probe;
  const std::optional<Eigen::Vector3d> probe_point = lab::ProbePoint(load);
  for (std::size_t i = 0; i < nodes.size(); ++i) {
    absl::StrAppend(&deck, i + 1, ", ", Coordinates(nodes[i]), "\n");
    if (const std::optional<Eigen::Vector3d> u = lab::HeldDisplacement(load, nodes[i])) {
      for (int c = 0; c < 3; ++c) {
        absl::StrAppendFormat(&held, "%d, %d, %d, %.12g\n", i + 1, c + 1, c + 1, (*u)[c]);
      }
      if (nodes[i].x() > lab::kBarLength / 2) absl::StrAppend(&pulled, i + 1, "\n");
    }
    if (probe_point.has_value() && (nodes[i] - *probe_point).norm() < 1e-9) {
      probe = absl::StrCat(i + 1, "\n");
    }
  }
  absl::StrAppend(&deck, elements);
  if (!pulled.empty()) absl::StrAppend(&deck, "*NSET, NSET=PULLED\n", pulled);
  if (!probe.empty()) absl::StrAppend(&deck, "*NSET, NSET=PROBE\n", probe);
  absl::StrAppend(&deck,
                  "*MATERIAL, NAME=TISSUE\n*ELASTIC\n5000., 0.45\n*DENSITY\n1.\n"
                  "*SOLID SECTION, ELSET=EALL, MATERIAL=TISSUE\n",
                  load == lab::BarLoad::kTwist ? "*STEP, NLGEOM, INC=1000\n*STATIC\n0.1, 1.\n"
                                               : "*STEP\n*STATIC\n",
                  "*BOUNDARY\n", held);
  if (load == lab::BarLoad::kCantilever)
    absl::StrAppend(&deck, "*DLOAD\nEALL, GRAV, 1., 0., 0., -1.\n");
  absl::StrAppend(&deck, probe_point.has_value() ? "*NODE PRINT, NSET=PROBE\nU\n"
                                                 : "*NODE PRINT, NSET=PULLED, TOTALS=ONLY\nRF\n");
  absl::StrAppend(&deck, "*END STEP\n");
  return deck;
}

// The three numbers after the last line of ccx's .dat that contains `header` (the final
// increment's): a node's displacement "id ux uy uz", or a set's total force "fx fy fz".
std::optional<Eigen::Vector3d> LastPrinted(const std::filesystem::path& dat,
                                           absl::string_view header) {
  std::ifstream in(dat);
  std::optional<Eigen::Vector3d> last;
  bool after_header = false;
  for (std::string line; std::getline(in, line);) {
    if (absl::StrContains(line, header)) {
      after_header = true;
      continue;
    }
    if (!after_header) continue;
    std::istringstream fields(line);
    std::vector<double> numbers;
    for (double x; fields >> x;) numbers.push_back(x);
    if (numbers.size() < 3) continue;
    last = Eigen::Vector3d(numbers[numbers.size() - 3], numbers[numbers.size() - 2],
                           numbers[numbers.size() - 1]);
    after_header = false;
  }
  return last;
}

}  // namespace

absl::StatusOr<Eigen::Vector3d> CalculixReference(lab::BarLoad load, int n) {
  absl::StatusOr<std::string> deck = Deck(load, n);
  if (!deck.ok()) return deck.status();
  absl::StatusOr<TemporaryFolder> folder = TemporaryFolder::Create("kerf-ccx");
  if (!folder.ok()) return folder.status();
  std::ofstream(folder->path() / "bar.inp") << *deck;
  if (absl::Status s = RunExternalProgram("ccx", {"-i", "bar"}, folder->path()); !s.ok()) {
    return s;
  }
  const std::optional<Eigen::Vector3d> quantity =
      LastPrinted(folder->path() / "bar.dat",
                  lab::ProbePoint(load).has_value() ? "displacements" : "total force");
  if (!quantity.has_value()) {
    return absl::InternalError(
        absl::StrCat("ccx printed no result for the ", lab::BarLoadName(load), " bar at n = ", n));
  }
  return *quantity;
}

}  // namespace kerf::cli
