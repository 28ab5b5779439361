// `kerf static` against CalculiX (ccx, installed by scripts/setup) on the same decks: the
// cantilever of ../shared/design/accuracy.md at n = 2, 4, 8 under a tip load and under
// gravity, and the shared liver under gravity with one end held. Every node's displacement
// must agree to 1e-6 of the largest displacement.
#include <gtest/gtest.h>

#include <Eigen/Geometry>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <map>
#include <sstream>
#include <string>

#include "absl/strings/str_cat.h"
#include "absl/strings/str_split.h"
#include "mesh/boundary_surface.h"
#include "mesh/box_lattice.h"
#include "mesh/io/mesh_file.h"
#include "support/run_command.h"
#include "support/shared_meshes.h"

namespace {

using kerf::mesh::TetMesh;
using kerf::mesh::VertexId;
using Displacements = std::map<std::int64_t, Eigen::Vector3d>;

std::string Run(const std::string& command, int* exit_code) {
  const kerf::testing::CommandResult result = kerf::testing::RunCommand(command);
  *exit_code = result.exit_code;
  return result.output;
}

struct Problem {
  TetMesh mesh;
  std::vector<VertexId> fixed;
  std::vector<std::pair<VertexId, double>> z_loads;  // CLOAD in dof 3
  bool gravity = false;                              // rho g = 1 downward (density 1)
};

// A deck in the accuracy.md subset; node id = vertex index + 1.
std::string Deck(const Problem& p) {
  std::string deck = "*HEADING\nkerf agreement test\n*NODE, NSET=NALL\n";
  char line[160];
  for (const VertexId v : p.mesh.vertices()) {
    const Eigen::Vector3d& x = p.mesh.rest_position(v);
    std::snprintf(line, sizeof(line), "%u, %.17g, %.17g, %.17g\n", kerf::mesh::Index(v) + 1, x.x(),
                  x.y(), x.z());
    deck += line;
  }
  deck += "*ELEMENT, TYPE=C3D4, ELSET=EALL\n";
  int element = 1;
  for (const auto t : p.mesh.tets()) {
    const auto& v = p.mesh.tet(t);
    absl::StrAppend(&deck, element++, ", ", kerf::mesh::Index(v[0]) + 1, ", ",
                    kerf::mesh::Index(v[1]) + 1, ", ", kerf::mesh::Index(v[2]) + 1, ", ",
                    kerf::mesh::Index(v[3]) + 1, "\n");
  }
  deck += "*NSET, NSET=FIX\n";
  for (const VertexId v : p.fixed) absl::StrAppend(&deck, kerf::mesh::Index(v) + 1, "\n");
  deck +=
      "*MATERIAL, NAME=TISSUE\n*ELASTIC\n5000., 0.45\n*DENSITY\n1.\n"
      "*SOLID SECTION, ELSET=EALL, MATERIAL=TISSUE\n*BOUNDARY\nFIX, 1, 3, 0.\n*STEP\n*STATIC\n";
  if (!p.z_loads.empty()) {
    deck += "*CLOAD\n";
    for (const auto& [v, f] : p.z_loads) {
      std::snprintf(line, sizeof(line), "%u, 3, %.17g\n", kerf::mesh::Index(v) + 1, f);
      deck += line;
    }
  }
  if (p.gravity) deck += "*DLOAD\nEALL, GRAV, 1., 0., 0., -1.\n";
  deck += "*NODE PRINT, NSET=NALL\nU\n*END STEP\n";
  return deck;
}

Displacements ParseCcxDat(const std::string& path) {
  std::ifstream in(path);
  Displacements u;
  std::string line;
  bool in_table = false;
  while (std::getline(in, line)) {
    if (line.find("displacements") != std::string::npos) {
      in_table = true;
      continue;
    }
    if (!in_table) continue;
    std::istringstream fields(line);
    std::int64_t id;
    Eigen::Vector3d d;
    if (fields >> id >> d.x() >> d.y() >> d.z()) u[id] = d;
  }
  return u;
}

Displacements ParseKerfJson(const std::string& json) {
  // {"displacements": {"1": [ux, uy, uz], ...}}
  Displacements u;
  const std::size_t open = json.find('{', 1);
  for (absl::string_view entry : absl::StrSplit(json.substr(open + 1), "], ")) {
    std::string text(entry);
    for (char& c : text) {
      if (c == '"' || c == ':' || c == '[' || c == ']' || c == ',' || c == '}') c = ' ';
    }
    std::istringstream fields(text);
    std::int64_t id;
    Eigen::Vector3d d;
    if (fields >> id >> d.x() >> d.y() >> d.z()) u[id] = d;
  }
  return u;
}

struct Comparison {
  double max_error;
  double max_displacement;
  Displacements kerf;
};

Comparison Compare(const Problem& problem, const std::string& name) {
  const std::filesystem::path dir = std::filesystem::path(::testing::TempDir()) / name;
  std::filesystem::create_directories(dir);
  EXPECT_TRUE(kerf::mesh::WriteTextFile((dir / "job.inp").string(), Deck(problem)).ok());
  int code = 0;
  const std::string ccx_log = Run(absl::StrCat("cd ", dir.string(), " && ccx -i job 2>&1"), &code);
  EXPECT_EQ(code, 0) << "ccx failed (is calculix-ccx installed by scripts/setup?)\n" << ccx_log;
  const Displacements reference = ParseCcxDat((dir / "job.dat").string());
  const std::string json =
      Run(absl::StrCat(KERF_BINARY, " static ", (dir / "job.inp").string(), " --json"), &code);
  EXPECT_EQ(code, 0) << json;
  const Displacements ours = ParseKerfJson(json);
  EXPECT_EQ(reference.size(), problem.mesh.vertex_count());
  EXPECT_EQ(ours.size(), reference.size());
  Comparison c{0, 0, ours};
  for (const auto& [id, d] : reference) {
    const auto it = ours.find(id);
    if (it == ours.end()) {
      ADD_FAILURE() << "kerf printed no displacement for node " << id;
      continue;
    }
    c.max_error = std::max(c.max_error, (it->second - d).lpNorm<Eigen::Infinity>());
    c.max_displacement = std::max(c.max_displacement, d.lpNorm<Eigen::Infinity>());
  }
  return c;
}

// The 5 x 1 x 1 bar as 5n x n x n cubes of six tets, clamped at x = 0.
Problem Cantilever(int n, bool tip_load) {
  kerf::mesh::BoxLatticeSpec spec;
  spec.cells_x = 5 * n;
  spec.cells_y = n;
  spec.cells_z = n;
  spec.size = {5, 1, 1};
  Problem p{*kerf::mesh::MakeBoxLattice(spec), {}, {}, !tip_load};
  for (const VertexId v : p.mesh.vertices()) {
    if (p.mesh.rest_position(v).x() == 0) p.fixed.push_back(v);
  }
  if (tip_load) {
    // Total P = 1 downward over the x = 5 face, each triangle's share split among its corners.
    std::map<VertexId, double> share;
    for (const auto& tri : kerf::mesh::ExtractBoundarySurface(p.mesh)) {
      const Eigen::Vector3d& a = p.mesh.rest_position(tri.vertices[0]);
      const Eigen::Vector3d& b = p.mesh.rest_position(tri.vertices[1]);
      const Eigen::Vector3d& c = p.mesh.rest_position(tri.vertices[2]);
      if (a.x() != 5 || b.x() != 5 || c.x() != 5) continue;
      const double area = 0.5 * (b - a).cross(c - a).norm();  // the face has area 1
      for (const VertexId v : tri.vertices) share[v] -= area / 3;
    }
    p.z_loads.assign(share.begin(), share.end());
  }
  return p;
}

double TipCentreDeflection(const Problem& p, const Displacements& u) {
  for (const VertexId v : p.mesh.vertices()) {
    if (p.mesh.rest_position(v) == Eigen::Vector3d(5, 0.5, 0.5)) {
      return -u.at(kerf::mesh::Index(v) + 1).z();
    }
  }
  return 0;
}

TEST(KerfStaticAgreesWithCalculix, CantileverTipLoadAndGravity) {
  for (const int n : {2, 4, 8}) {
    for (const bool tip : {true, false}) {
      const Problem problem = Cantilever(n, tip);
      const Comparison c = Compare(problem, absl::StrCat("cantilever_", n, tip ? "_tip" : "_grav"));
      EXPECT_GT(c.max_displacement, 0);
      EXPECT_LE(c.max_error, 1e-6 * c.max_displacement) << "n = " << n << (tip ? " tip" : " grav");
      std::printf(
          "cantilever n=%d %s: tip-centre deflection %.5f, max |kerf - ccx| / max |u| = "
          "%.2e\n",
          n, tip ? "tip " : "grav", TipCentreDeflection(problem, c.kerf),
          c.max_error / c.max_displacement);
    }
  }
}

TEST(KerfStaticAgreesWithCalculix, LiverUnderGravityHeldAtOneEnd) {
  const std::string path = kerf::testing::SharedMeshPath("liver.msh");
  if (path.empty()) GTEST_SKIP() << "shared/meshes is not beside the repo";
  Problem problem{*kerf::mesh::ReadMeshFile(path), {}, {}, true};
  double max_x = -1e300;
  for (const VertexId v : problem.mesh.vertices()) {
    max_x = std::max(max_x, problem.mesh.rest_position(v).x());
  }
  for (const VertexId v : problem.mesh.vertices()) {
    if (problem.mesh.rest_position(v).x() > max_x - 1.0) problem.fixed.push_back(v);
  }
  ASSERT_GE(problem.fixed.size(), 10u);
  const Comparison c = Compare(problem, "liver_grav");
  EXPECT_GT(c.max_displacement, 0);
  EXPECT_LE(c.max_error, 1e-6 * c.max_displacement);
  std::printf("liver, gravity, %zu nodes held: max |u| %.5f, max |kerf - ccx| / max |u| = %.2e\n",
              problem.fixed.size(), c.max_displacement, c.max_error / c.max_displacement);
}

}  // namespace
