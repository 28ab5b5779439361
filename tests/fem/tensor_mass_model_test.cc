#include "fem/tensor_mass_model.h"

#include <gtest/gtest.h>

#include <random>

#include "absl/strings/str_cat.h"
#include "fem/linear_tet_element.h"
#include "mesh/box_lattice.h"
#include "support/status_message.h"

namespace kerf::fem {
namespace {

using kerf::testing::StatusMessage;
using mesh::Index;
using mesh::TetId;
using mesh::VertexId;

Material Tissue() {
  Material m;
  m.youngs_modulus = 5000;
  m.poisson_ratio = 0.45;
  m.density = 1000;
  return m;
}

mesh::TetMesh Lattice(int nx, int ny, int nz) {
  mesh::BoxLatticeSpec spec;
  spec.cells_x = nx;
  spec.cells_y = ny;
  spec.cells_z = nz;
  spec.size = {0.01 * nx, 0.012 * ny, 0.009 * nz};
  return *mesh::MakeBoxLattice(spec);
}

// K assembled element by element from the 12x12 matrices, without the tensor store.
Eigen::MatrixXd AssembleDirectly(const mesh::TetMesh& m, const Material& material) {
  const LameParameters lame = CalcLameParameters(material.youngs_modulus, material.poisson_ratio);
  const Eigen::Index n = 3 * m.vertex_index_bound();
  Eigen::MatrixXd k = Eigen::MatrixXd::Zero(n, n);
  for (const TetId t : m.tets()) {
    const mesh::TetVertices& v = m.tet(t);
    const LinearTetStiffness ke =
        ComputeLinearTetStiffness({m.rest_position(v[0]), m.rest_position(v[1]),
                                   m.rest_position(v[2]), m.rest_position(v[3])},
                                  lame);
    for (int a = 0; a < 4; ++a) {
      for (int b = 0; b < 4; ++b)
        k.block<3, 3>(3 * Index(v[a]), 3 * Index(v[b])) += ke.blocks[a][b];
    }
  }
  return k;
}

std::vector<Eigen::Vector3d> RandomField(std::size_t n, int seed) {
  std::mt19937 random(seed);
  std::uniform_real_distribution<double> uniform(-1e-3, 1e-3);
  std::vector<Eigen::Vector3d> u(n);
  for (auto& x : u) x = Eigen::Vector3d(uniform(random), uniform(random), uniform(random));
  return u;
}

Eigen::VectorXd Flatten(const std::vector<Eigen::Vector3d>& u) {
  Eigen::VectorXd flat(3 * static_cast<Eigen::Index>(u.size()));
  for (std::size_t i = 0; i < u.size(); ++i)
    flat.segment<3>(3 * static_cast<Eigen::Index>(i)) = u[i];
  return flat;
}

TEST(TensorMassModel, TensorsTimesUEqualIndependentlyAssembledK) {
  const mesh::TetMesh m = Lattice(3, 2, 2);
  const TensorMassModel model = *TensorMassModel::Create(m, Tissue());
  const std::vector<Eigen::Vector3d> u = RandomField(m.vertex_index_bound(), 1);
  std::vector<Eigen::Vector3d> f(u.size());
  model.MultiplyStiffness(u, f);
  const Eigen::VectorXd expected = AssembleDirectly(m, Tissue()) * Flatten(u);
  EXPECT_LT((Flatten(f) - expected).norm(), 1e-12 * expected.norm());
  // The assembled sparse matrix agrees too.
  const Eigen::VectorXd sparse = model.AssembleStiffness() * Flatten(u);
  EXPECT_LT((sparse - expected).norm(), 1e-12 * expected.norm());
}

TEST(TensorMassModel, RigidTranslationGivesZeroForce) {
  const mesh::TetMesh m = Lattice(2, 2, 2);
  const TensorMassModel model = *TensorMassModel::Create(m, Tissue());
  std::vector<Eigen::Vector3d> u(m.vertex_index_bound(), Eigen::Vector3d(0.3, -0.2, 0.1));
  std::vector<Eigen::Vector3d> f(u.size());
  model.MultiplyStiffness(u, f);
  const std::vector<Eigen::Vector3d> random = RandomField(u.size(), 2);
  std::vector<Eigen::Vector3d> f_random(u.size());
  model.MultiplyStiffness(random, f_random);
  EXPECT_LT(Flatten(f).norm(), 1e-12 * Flatten(f_random).norm() / Flatten(random).norm() * 0.3);
}

TEST(TensorMassModel, ForceIsTheGradientOfTheElasticEnergy) {
  // f = K u is the gradient of E(u) = u^T K u / 2; the elastic force on the vertices, -f, is
  // minus the gradient. Central differences are exact for a quadratic up to rounding.
  const mesh::TetMesh m = Lattice(2, 1, 1);
  const TensorMassModel model = *TensorMassModel::Create(m, Tissue());
  std::vector<Eigen::Vector3d> u = RandomField(m.vertex_index_bound(), 3);
  std::vector<Eigen::Vector3d> f(u.size());
  model.MultiplyStiffness(u, f);
  const double h = 1e-6;
  for (std::size_t i = 0; i < u.size(); ++i) {
    for (int c = 0; c < 3; ++c) {
      const double original = u[i][c];
      u[i][c] = original + h;
      const double plus = model.ElasticEnergy(u);
      u[i][c] = original - h;
      const double minus = model.ElasticEnergy(u);
      u[i][c] = original;
      EXPECT_NEAR((plus - minus) / (2 * h), f[i][c], 1e-6 * Flatten(f).lpNorm<Eigen::Infinity>());
    }
  }
}

TEST(TensorMassModel, LumpedMassIsDensityTimesVolume) {
  const mesh::TetMesh m = Lattice(3, 3, 2);
  const TensorMassModel model = *TensorMassModel::Create(m, Tissue());
  double total = 0;
  for (const double mass : model.masses()) total += mass;
  EXPECT_NEAR(total, 1000 * 0.03 * 0.036 * 0.018, 1e-15);
  // A corner vertex of the box belongs to one or two tets of the Kuhn split.
  EXPECT_GT(model.mass(VertexId{0}), 0);
}

// Each edge is listed at both its ends and nowhere else, and the product row by row (every
// other active vertex) is the whole product's rows, the others left as they were.
void ExpectRowsMatchTheProduct(const TensorMassModel& model) {
  std::size_t listed = 0;
  for (std::uint32_t i = 0; i < model.vertex_count(); ++i) {
    for (const std::uint32_t slot : model.edges_at(i)) {
      ASSERT_LT(slot, model.edges().size());
      const EdgeTensor& e = model.edges()[slot];
      EXPECT_TRUE(Index(e.a) == i || Index(e.b) == i) << i;
      ++listed;
    }
  }
  EXPECT_EQ(listed, 2 * model.edges().size());
  const std::vector<Eigen::Vector3d> u = RandomField(model.vertex_count(), 9);
  std::vector<Eigen::Vector3d> whole(u.size(), Eigen::Vector3d::Zero());
  model.MultiplyStiffness(u, whole);
  std::vector<std::uint32_t> rows;
  for (std::size_t k = 0; k < model.active_vertices().size(); k += 2) {
    rows.push_back(model.active_vertices()[k]);
  }
  const Eigen::Vector3d untouched(7, 7, 7);
  std::vector<Eigen::Vector3d> by_rows(u.size(), untouched);
  model.MultiplyStiffnessRows(rows, u, by_rows);
  double scale = 0;
  for (const Eigen::Vector3d& f : whole) scale = std::max(scale, f.norm());
  std::vector<bool> in_rows(u.size(), false);
  for (const std::uint32_t i : rows) in_rows[i] = true;
  for (std::uint32_t i = 0; i < u.size(); ++i) {
    if (in_rows[i]) {
      EXPECT_LE((by_rows[i] - whole[i]).norm(), 1e-12 * scale) << i;
    } else {
      EXPECT_EQ(by_rows[i], untouched) << i;
    }
  }
}

void ExpectModelsEqual(const TensorMassModel& a, const TensorMassModel& b) {
  ASSERT_EQ(a.vertex_count(), b.vertex_count());
  double scale = 0;
  for (std::size_t i = 0; i < a.vertex_count(); ++i) {
    scale = std::max(scale, b.vertex_tensor(static_cast<VertexId>(i)).norm());
  }
  const double mass_scale = *std::max_element(b.masses().begin(), b.masses().end());
  for (std::size_t i = 0; i < a.vertex_count(); ++i) {
    const auto v = static_cast<VertexId>(i);
    EXPECT_LE((a.vertex_tensor(v) - b.vertex_tensor(v)).norm(), 1e-12 * scale) << i;
    EXPECT_LE(std::abs(a.mass(v) - b.mass(v)), 1e-12 * mass_scale) << i;
  }
  ASSERT_EQ(a.edges().size(), b.edges().size());
  for (const EdgeTensor& e : b.edges()) {
    const EdgeTensor* other = a.FindEdge(e.a, e.b);
    ASSERT_NE(other, nullptr);
    EXPECT_LE((other->k_ab - e.k_ab).norm(), 1e-12 * scale);
    EXPECT_EQ(other->tets, e.tets);
  }
  EXPECT_EQ(std::vector<std::uint32_t>(a.active_vertices().begin(), a.active_vertices().end()),
            std::vector<std::uint32_t>(b.active_vertices().begin(), b.active_vertices().end()));
  ExpectRowsMatchTheProduct(a);
}

TEST(TensorMassModel, IncrementalChangesEqualARebuildFromScratch) {
  mesh::TetMesh m = Lattice(4, 3, 3);
  TensorMassModel model = *TensorMassModel::Create(m, Tissue());
  std::mt19937 random(11);
  std::vector<mesh::TetVertices> removed;
  for (int round = 0; round < 50; ++round) {
    // A burst of changes, as one cut makes, then a sync.
    for (int op = 0; op < 20; ++op) {
      std::vector<TetId> live(m.tets().begin(), m.tets().end());
      if (random() % 3 != 0 || removed.empty()) {
        const TetId t = live[random() % live.size()];
        removed.push_back(m.tet(t));
        ASSERT_TRUE(m.RemoveTet(t).ok());
      } else {
        const std::size_t i = random() % removed.size();
        ASSERT_TRUE(m.AddTet(removed[i]).ok());
        removed.erase(removed.begin() + static_cast<std::ptrdiff_t>(i));
      }
      if (op == 7) {
        // A new vertex splitting a live tet's corner region, as a cut adds vertices.
        const TetId t = *m.tets().begin();
        const mesh::TetVertices v = m.tet(t);
        const VertexId extra = m.AddVertex(0.25 * (m.rest_position(v[0]) + m.rest_position(v[1]) +
                                                   m.rest_position(v[2]) + m.rest_position(v[3])));
        ASSERT_TRUE(m.RemoveTet(t).ok());
        for (const auto& face : mesh::kTetFaces) {
          ASSERT_TRUE(m.AddTet({v[face[0]], v[face[1]], v[face[2]], extra}).ok());
        }
      }
    }
    ASSERT_TRUE(model.SyncWithMesh().ok());
  }
  ExpectModelsEqual(model, *TensorMassModel::Create(m, Tissue()));
}

// A progressive cut moves its temporary points in place: the tets around them take their new
// shape at the next sync, as if they had been built with it.
TEST(TensorMassModel, MovedVerticesEqualARebuildFromScratch) {
  mesh::TetMesh m = Lattice(3, 3, 3);
  TensorMassModel model = *TensorMassModel::Create(m, Tissue());
  std::mt19937 random(5);
  std::uniform_real_distribution<double> nudge(-0.002, 0.002);
  for (int round = 0; round < 20; ++round) {
    for (int k = 0; k < 3; ++k) {
      const VertexId v = static_cast<VertexId>(random() % m.vertex_index_bound());
      const Eigen::Vector3d moved =
          m.rest_position(v) + Eigen::Vector3d(nudge(random), nudge(random), nudge(random));
      ASSERT_TRUE(m.MoveVertex(v, moved, moved).ok());
    }
    if (round % 4 == 0) {
      ASSERT_TRUE(m.RemoveTet(*m.tets().begin()).ok());  // mixed with removals
    }
    ASSERT_TRUE(model.SyncWithMesh().ok());
  }
  ExpectModelsEqual(model, *TensorMassModel::Create(m, Tissue()));
}

// Splitting a tet keeps the mass. Pieces given a stiffness scale (a progressive cut's
// temporary slivers) bring all their mass and that share of their stiffness, and are taken
// away as they were added even if their scale has changed since.
TEST(TensorMassModel, SplitPiecesKeepTheMassAndScaledPiecesThatShareOfStiffness) {
  mesh::TetMesh m = Lattice(2, 2, 2);
  TensorMassModel model = *TensorMassModel::Create(m, Tissue());
  double before = 0;
  for (const double mass : model.masses()) before += mass;
  const mesh::TetVertices v = m.tet(TetId{5});
  const VertexId centre = m.AddVertex(0.25 * (m.rest_position(v[0]) + m.rest_position(v[1]) +
                                              m.rest_position(v[2]) + m.rest_position(v[3])));
  ASSERT_TRUE(m.RemoveTet(TetId{5}).ok());
  std::vector<TetId> pieces;
  for (const auto& face : mesh::kTetFaces) {
    pieces.push_back(*m.AddTet({v[face[0]], v[face[1]], v[face[2]], centre}));
  }
  model.SetStiffnessScale(
      [&](TetId t) { return mesh::TetHasVertex(m.tet(t), centre) ? 0.5 : 1.0; });
  ASSERT_TRUE(model.SyncWithMesh().ok());
  double after = 0;
  for (const double mass : model.masses()) after += mass;
  EXPECT_NEAR(after, before, 1e-15 * before);
  EXPECT_GT(model.mass(centre), 0);
  // K u is that of the mesh without the pieces plus half theirs.
  mesh::TetMesh without = m;
  for (const TetId piece : pieces) ASSERT_TRUE(without.RemoveTet(piece).ok());
  const Eigen::MatrixXd k_without = AssembleDirectly(without, Tissue());
  const Eigen::MatrixXd k_full = AssembleDirectly(m, Tissue());
  const std::vector<Eigen::Vector3d> u = RandomField(m.vertex_index_bound(), 3);
  std::vector<Eigen::Vector3d> f(u.size(), Eigen::Vector3d::Zero());
  model.MultiplyStiffness(u, f);
  const Eigen::VectorXd expected = (0.5 * (k_full + k_without)) * Flatten(u);
  EXPECT_LE((Flatten(f) - expected).norm(), 1e-9 * expected.norm());
  EXPECT_GT((Flatten(f) - k_full * Flatten(u)).norm(), 1e-3 * expected.norm());

  model.SetStiffnessScale(nullptr);
  for (const TetId piece : pieces) ASSERT_TRUE(m.RemoveTet(piece).ok());
  ASSERT_TRUE(m.AddTet(v).ok());
  ASSERT_TRUE(model.SyncWithMesh().ok());
  ExpectModelsEqual(model, *TensorMassModel::Create(m, Tissue()));
}

TEST(TensorMassModel, RefusesFlatTetsAndBadMaterialsAndChangesNothing) {
  mesh::TetMesh m = Lattice(1, 1, 1);
  Material bad = Tissue();
  bad.poisson_ratio = 0.5;
  EXPECT_EQ(StatusMessage(TensorMassModel::Create(m, bad)),
            "poisson_ratio must be strictly between -1 and 0.5, got 0.5");

  TensorMassModel model = *TensorMassModel::Create(m, Tissue());
  const double mass_before = model.mass(VertexId{0});
  const VertexId flat =
      m.AddVertex(m.rest_position(VertexId{0}) * 0.5 + m.rest_position(VertexId{1}) * 0.5);
  const TetId t = *m.AddTet({VertexId{0}, VertexId{1}, flat, VertexId{2}});
  ASSERT_TRUE(m.RemoveTet(TetId{0}).ok());
  EXPECT_EQ(StatusMessage(model.SyncWithMesh()),
            absl::StrCat("tet ", Index(t), " has zero rest volume: its stiffness is undefined"));
  EXPECT_EQ(model.mass(VertexId{0}), mass_before);
  EXPECT_EQ(StatusMessage(TensorMassModel::Create(m, Tissue())),
            absl::StrCat("tet ", Index(t), " has zero rest volume: its stiffness is undefined"));
}

}  // namespace
}  // namespace kerf::fem
