#include "lab/crack_fidelity.h"

#include <Eigen/Dense>
#include <Eigen/Geometry>
#include <algorithm>
#include <cmath>
#include <random>
#include <tuple>

#include "absl/container/flat_hash_map.h"
#include "absl/container/flat_hash_set.h"
#include "geometry/point_triangle_distance.h"
#include "geometry/tet_measures.h"
#include "mesh/boundary_surface.h"
#include "mesh/mesh_quality.h"

namespace kerf::lab {
namespace {

using Polygon = std::vector<Eigen::Vector3d>;

double TriangleArea(const Eigen::Vector3d& a, const Eigen::Vector3d& b, const Eigen::Vector3d& c) {
  return 0.5 * (b - a).cross(c - a).norm();
}

// The part of `polygon` (convex, planar) inside the tet: clipped by each face's plane in turn.
Polygon ClipToTet(Polygon polygon, const std::array<Eigen::Vector3d, 4>& corners) {
  for (int k = 0; k < 4 && !polygon.empty(); ++k) {
    const Eigen::Vector3d& p = corners[(k + 1) % 4];
    Eigen::Vector3d normal = (corners[(k + 2) % 4] - p).cross(corners[(k + 3) % 4] - p);
    if (normal.dot(corners[k] - p) < 0) normal = -normal;  // inward
    Polygon clipped;
    for (std::size_t i = 0; i < polygon.size(); ++i) {
      const Eigen::Vector3d& a = polygon[i];
      const Eigen::Vector3d& b = polygon[(i + 1) % polygon.size()];
      const double da = normal.dot(a - p), db = normal.dot(b - p);
      if (da >= 0) clipped.push_back(a);
      if ((da >= 0) != (db >= 0)) clipped.push_back(a + da / (da - db) * (b - a));
    }
    polygon = std::move(clipped);
  }
  return polygon.size() >= 3 ? polygon : Polygon{};
}

// A seeded point, uniform on a convex polygon.
Eigen::Vector3d PointOn(const std::vector<Eigen::Vector3d>& polygon, std::mt19937_64& random) {
  std::uniform_real_distribution<double> unit(0, 1);
  std::vector<double> cumulative;
  double area = 0;
  for (std::size_t k = 1; k + 1 < polygon.size(); ++k) {
    area += TriangleArea(polygon[0], polygon[k], polygon[k + 1]);
    cumulative.push_back(area);
  }
  const std::size_t k = std::min<std::size_t>(
      std::lower_bound(cumulative.begin(), cumulative.end(), unit(random) * area) -
          cumulative.begin(),
      cumulative.size() - 1);
  double u = unit(random), v = unit(random);
  if (u + v > 1) u = 1 - u, v = 1 - v;
  return polygon[0] + u * (polygon[k + 1] - polygon[0]) + v * (polygon[k + 2] - polygon[0]);
}

using PointKey = std::tuple<double, double, double>;
PointKey KeyOf(const Eigen::Vector3d& p) { return {p.x(), p.y(), p.z()}; }

}  // namespace

bool CrackFaces::Within(const Eigen::Vector3d& p, double radius) const {
  for (const std::uint32_t i : index_.Near(p, radius)) {
    const std::array<Eigen::Vector3d, 3>& t = triangles_[i];
    if (geometry::DistanceToTriangle(p, t[0], t[1], t[2]) <= radius) return true;
  }
  return false;
}

FidelityMeter::FidelityMeter(const mesh::TetMesh& tissue, const FidelityOptions& options)
    : options_(options),
      mean_edge_(mesh::MeanEdgeLength(tissue)),
      tet_index_(mean_edge_),
      boundary_index_(mean_edge_),
      swept_index_(mean_edge_) {
  for (const mesh::TetId t : tissue.tets()) {
    const mesh::TetVertices& v = tissue.tet(t);
    std::array<Eigen::Vector3d, 4> c;
    Eigen::Vector3d low = Eigen::Vector3d::Constant(HUGE_VAL), high = -low;
    for (int k = 0; k < 4; ++k) {
      c[k] = tissue.rest_position(v[k]);
      low = low.cwiseMin(c[k]);
      high = high.cwiseMax(c[k]);
    }
    double edges = 0;
    for (int i = 0; i < 4; ++i) {
      for (int j = i + 1; j < 4; ++j) {
        edges += (c[i] - c[j]).norm();
        longest_edge_ = std::max(longest_edge_, (c[i] - c[j]).norm());
      }
    }
    tet_index_.Add(static_cast<std::uint32_t>(tets_.size()), low, high);
    tets_.push_back(c);
    tet_edge_.push_back(edges / 6);
  }
  absl::flat_hash_map<mesh::TetId, std::uint32_t> index_of;
  for (const mesh::TetId t : tissue.tets())
    index_of[t] = static_cast<std::uint32_t>(index_of.size());
  boundary_face_.assign(tets_.size(), {false, false, false, false});
  for (const mesh::BoundaryTriangle& b : mesh::ExtractBoundarySurface(tissue)) {
    boundary_face_[index_of.at(b.tet)][b.opposite_corner] = true;
    std::array<Eigen::Vector3d, 3> t;
    for (int k = 0; k < 3; ++k) t[k] = tissue.rest_position(b.vertices[k]);
    boundary_index_.Add(static_cast<std::uint32_t>(boundary_.size()),
                        t[0].cwiseMin(t[1]).cwiseMin(t[2]), t[0].cwiseMax(t[1]).cwiseMax(t[2]));
    boundary_.push_back(t);
  }
}

std::size_t FidelityMeter::AddStep(const cut::BladePose& from, const cut::BladePose& to) {
  const std::uint64_t step = step_end_.size();
  const std::array<std::array<Eigen::Vector3d, 3>, 2> triangles = {
      {{from.tip, from.heel, to.heel}, {from.tip, to.heel, to.tip}}};
  for (int i = 0; i < 2; ++i) {
    const std::array<Eigen::Vector3d, 3>& t = triangles[i];
    if (TriangleArea(t[0], t[1], t[2]) <= 0) continue;
    swept_index_.Add(static_cast<std::uint32_t>(swept_.size()), t[0].cwiseMin(t[1]).cwiseMin(t[2]),
                     t[0].cwiseMax(t[1]).cwiseMax(t[2]));
    swept_.push_back(t);
    AddTriangle(t, options_.seed * 0x9e3779b97f4a7c15ull + 2 * step + i);
  }
  step_end_.push_back(step_samples_.size());
  return step;
}

void FidelityMeter::AddTriangle(const std::array<Eigen::Vector3d, 3>& t, std::uint64_t seed) {
  std::mt19937_64 random(seed);
  const Eigen::Vector3d low = t[0].cwiseMin(t[1]).cwiseMin(t[2]);
  const Eigen::Vector3d high = t[0].cwiseMax(t[1]).cwiseMax(t[2]);
  for (const std::uint32_t tet : tet_index_.InBox(low, high)) {
    Polygon piece = ClipToTet({t[0], t[1], t[2]}, tets_[tet]);
    if (piece.empty() || OnBoundary(piece, tet)) continue;
    double area = 0;
    for (std::size_t k = 1; k + 1 < piece.size(); ++k) {
      area += TriangleArea(piece[0], piece[k], piece[k + 1]);
    }
    if (area <= 1e-9 * tet_edge_[tet] * tet_edge_[tet]) continue;  // a piece on an edge or corner
    const double edge = tet_edge_[tet];
    const int n = std::max(1, static_cast<int>(std::ceil(options_.step_samples_per_square_edge *
                                                         area / (edge * edge))));
    for (int s = 0; s < n; ++s) step_samples_.push_back(MakeSample(PointOn(piece, random), tet));
    pieces_.push_back({tet, std::move(piece), area});
  }
}

FidelityMeter::Sample FidelityMeter::MakeSample(const Eigen::Vector3d& p, std::uint32_t tet) const {
  const double edge = tet_edge_[tet], radius = options_.tolerance * edge;
  bool at_surface = false;
  for (const std::uint32_t i : boundary_index_.Near(p, radius)) {
    const std::array<Eigen::Vector3d, 3>& b = boundary_[i];
    if (geometry::DistanceToTriangle(p, b[0], b[1], b[2]) <= radius) {
      at_surface = true;
      break;
    }
  }
  return {p, edge, tet, at_surface};
}

bool FidelityMeter::OnBoundary(const std::vector<Eigen::Vector3d>& piece, std::uint32_t tet) const {
  const std::array<Eigen::Vector3d, 4>& c = tets_[tet];
  for (int k = 0; k < 4; ++k) {
    if (!boundary_face_[tet][k]) continue;
    const Eigen::Vector3d& p = c[(k + 1) % 4];
    const Eigen::Vector3d normal = (c[(k + 2) % 4] - p).cross(c[(k + 3) % 4] - p).normalized();
    if (std::all_of(piece.begin(), piece.end(), [&](const Eigen::Vector3d& x) {
          return std::abs(normal.dot(x - p)) <= 1e-9 * tet_edge_[tet];
        })) {
      return true;
    }
  }
  return false;
}

const std::vector<FidelityMeter::Sample>& FidelityMeter::Samples() const {
  if (sampled_pieces_ == pieces_.size() && !samples_.empty()) return samples_;
  samples_.clear();
  sampled_pieces_ = pieces_.size();
  absl::flat_hash_map<std::uint32_t, std::vector<const Piece*>> by_tet;
  for (const Piece& p : pieces_) by_tet[p.tet].push_back(&p);
  std::vector<std::uint32_t> tets;
  for (const auto& [tet, pieces] : by_tet) tets.push_back(tet);
  std::sort(tets.begin(), tets.end());  // the same samples whatever the map's order
  for (const std::uint32_t tet : tets) {
    const std::vector<const Piece*>& pieces = by_tet[tet];
    std::mt19937_64 random(options_.seed * 0x9e3779b97f4a7c15ull + tet);
    std::uniform_real_distribution<double> unit(0, 1);
    std::vector<double> cumulative;
    double area = 0;
    for (const Piece* p : pieces) cumulative.push_back(area += p->area);
    const double edge = tet_edge_[tet];
    const int n = std::max(
        options_.min_samples_per_tet,
        static_cast<int>(std::ceil(options_.samples_per_square_edge * area / (edge * edge))));
    for (int s = 0; s < n; ++s) {
      const std::size_t k = std::min<std::size_t>(
          std::lower_bound(cumulative.begin(), cumulative.end(), unit(random) * area) -
              cumulative.begin(),
          pieces.size() - 1);
      samples_.push_back(MakeSample(PointOn(pieces[k]->polygon, random), tet));
    }
  }
  return samples_;
}

double FidelityMeter::LocalEdgeLength(const Eigen::Vector3d& p) const {
  double best = -HUGE_VAL, edge = mean_edge_;
  for (const std::uint32_t tet : tet_index_.Near(p, 0)) {
    const std::array<Eigen::Vector3d, 4>& c = tets_[tet];
    const double inside = geometry::BarycentricWeights(c[0], c[1], c[2], c[3], p).minCoeff();
    if (inside > best) best = inside, edge = tet_edge_[tet];
  }
  return edge;
}

void CrackFaces::Add(const std::array<Eigen::Vector3d, 3>& t) {
  index_.Add(static_cast<std::uint32_t>(triangles_.size()), t[0].cwiseMin(t[1]).cwiseMin(t[2]),
             t[0].cwiseMax(t[1]).cwiseMax(t[2]));
  triangles_.push_back(t);
}

bool FidelityMeter::InTissueBoundary(const std::array<Eigen::Vector3d, 3>& t) const {
  const double on_boundary = 1e-9 * mean_edge_;
  const Eigen::Vector3d middle = (t[0] + t[1] + t[2]) / 3;
  const double radius =
      std::max({(t[0] - middle).norm(), (t[1] - middle).norm(), (t[2] - middle).norm()});
  for (const std::uint32_t i : boundary_index_.Near(middle, radius + on_boundary)) {
    const std::array<Eigen::Vector3d, 3>& o = boundary_[i];
    if (std::all_of(t.begin(), t.end(), [&](const Eigen::Vector3d& p) {
          return geometry::DistanceToTriangle(p, o[0], o[1], o[2]) <= on_boundary;
        })) {
      return true;
    }
  }
  return false;
}

CrackFaces FidelityMeter::FindCrack(const mesh::TetMesh& cut) const {
  CrackFaces crack(mean_edge_);
  absl::flat_hash_map<std::array<PointKey, 3>, int> count;
  std::vector<std::array<PointKey, 3>> keys;
  for (const mesh::BoundaryTriangle& b : mesh::ExtractBoundarySurface(cut)) {
    std::array<Eigen::Vector3d, 3> t;
    for (int k = 0; k < 3; ++k) t[k] = cut.rest_position(b.vertices[k]);
    if (InTissueBoundary(t)) continue;
    std::array<PointKey, 3> key = {KeyOf(t[0]), KeyOf(t[1]), KeyOf(t[2])};
    std::sort(key.begin(), key.end());
    ++count[key];
    keys.push_back(key);
    crack.Add(t);
  }
  for (const std::array<PointKey, 3>& key : keys) {
    if (count[key] < 2) ++crack.unpaired_;
  }
  return crack;
}

CrackFaces FidelityMeter::FindCrackNearStep(const mesh::TetMesh& cut, std::size_t k) const {
  CrackFaces crack(mean_edge_);
  if (StepSamples(k) == 0) return crack;
  Eigen::Vector3d low = Eigen::Vector3d::Constant(HUGE_VAL), high = -low;
  for (std::size_t i = StepBegin(k); i < step_end_[k]; ++i) {
    const Sample& s = step_samples_[i];
    const double reach = options_.tolerance * s.edge + longest_edge_;
    low = low.cwiseMin(s.point - Eigen::Vector3d::Constant(reach));
    high = high.cwiseMax(s.point + Eigen::Vector3d::Constant(reach));
  }
  absl::flat_hash_set<std::array<mesh::VertexId, 3>> seen;
  for (const mesh::VertexId v : cut.vertices()) {
    const Eigen::Vector3d& x = cut.rest_position(v);
    if ((x.array() < low.array()).any() || (x.array() > high.array()).any()) continue;
    for (const mesh::TetId t : cut.TetsAround(v)) {
      const mesh::TetVertices& c = cut.tet(t);
      for (const auto& face : mesh::kTetFaces) {
        std::array<mesh::VertexId, 3> key = {c[face[0]], c[face[1]], c[face[2]]};
        std::sort(key.begin(), key.end());
        if (!seen.insert(key).second || cut.TetsAroundFace(key[0], key[1], key[2]).size() != 1) {
          continue;
        }
        const std::array<Eigen::Vector3d, 3> triangle = {
            cut.rest_position(key[0]), cut.rest_position(key[1]), cut.rest_position(key[2])};
        if (!InTissueBoundary(triangle)) crack.Add(triangle);
      }
    }
  }
  return crack;
}

bool FidelityMeter::Covered(const CrackFaces& crack, const Sample& s) const {
  return crack.Within(s.point, options_.tolerance * s.edge);
}

Fidelity FidelityMeter::Measure(const CrackFaces& crack) const {
  Fidelity f;
  const std::vector<Sample>& samples = Samples();
  f.samples = samples.size();
  std::size_t covered_below = 0;
  for (const Sample& s : samples) {
    const bool covered = Covered(crack, s);
    f.covered += covered ? 1 : 0;
    f.surface_samples += s.at_surface ? 1 : 0;
    covered_below += covered && !s.at_surface ? 1 : 0;
  }
  f.coverage = f.samples ? static_cast<double>(f.covered) / static_cast<double>(f.samples) : 1;
  const std::size_t below = f.samples - f.surface_samples;
  f.coverage_below_surface =
      below ? static_cast<double>(covered_below) / static_cast<double>(below) : 1;
  f.crack_faces = crack.size();
  f.unpaired_faces = crack.unpaired();
  for (const std::array<Eigen::Vector3d, 3>& t : crack.triangles()) {
    const FaceDistance d = DistanceFromSweep(t);
    f.max_overcut = std::max(f.max_overcut, d.farthest());
    if (IsOvercut(d)) ++f.overcut_faces;
  }
  return f;
}

FidelityMeter::FaceDistance FidelityMeter::DistanceFromSweep(
    const std::array<Eigen::Vector3d, 3>& t) const {
  const Eigen::Vector3d middle = (t[0] + t[1] + t[2]) / 3;
  FaceDistance d{.triangle = t, .distance = {}, .edge = LocalEdgeLength(middle)};
  const double cap = 2 * options_.tolerance * d.edge;
  const std::array<Eigen::Vector3d, 4> points = {t[0], t[1], t[2], middle};
  for (std::size_t k = 0; k < points.size(); ++k) {
    double nearest = cap;
    for (const std::uint32_t i : swept_index_.Near(points[k], cap)) {
      const std::array<Eigen::Vector3d, 3>& s = swept_[i];
      nearest = std::min(nearest, geometry::DistanceToTriangle(points[k], s[0], s[1], s[2]));
    }
    d.distance[k] = nearest / d.edge;
  }
  return d;
}

std::vector<FidelityMeter::FaceDistance> FidelityMeter::Overcut(const CrackFaces& crack) const {
  std::vector<FaceDistance> overcut;
  for (const std::array<Eigen::Vector3d, 3>& t : crack.triangles()) {
    FaceDistance d = DistanceFromSweep(t);
    if (IsOvercut(d)) overcut.push_back(std::move(d));
  }
  return overcut;
}

std::vector<std::pair<Eigen::Vector3d, double>> FidelityMeter::Uncovered(
    const CrackFaces& crack) const {
  std::vector<std::pair<Eigen::Vector3d, double>> uncovered;
  for (const Sample& s : Samples()) {
    if (!Covered(crack, s)) uncovered.push_back({s.point, s.edge});
  }
  return uncovered;
}

double FidelityMeter::StepCoverage(const CrackFaces& crack, std::size_t k) const {
  const std::size_t begin = StepBegin(k), end = step_end_[k];
  if (begin == end) return 1;
  std::size_t covered = 0;
  for (std::size_t i = begin; i < end; ++i) covered += Covered(crack, step_samples_[i]) ? 1 : 0;
  return static_cast<double>(covered) / static_cast<double>(end - begin);
}

double FidelityMeter::StepCoverageBelowSurface(const CrackFaces& crack, std::size_t k) const {
  std::size_t below = 0, covered = 0;
  for (std::size_t i = StepBegin(k); i < step_end_[k]; ++i) {
    if (step_samples_[i].at_surface) continue;
    ++below;
    covered += Covered(crack, step_samples_[i]) ? 1 : 0;
  }
  return below == 0 ? 1 : static_cast<double>(covered) / static_cast<double>(below);
}

std::vector<FidelityMeter::UncoveredSample> FidelityMeter::StepUncovered(const CrackFaces& crack,
                                                                         std::size_t k) const {
  std::vector<UncoveredSample> uncovered;
  for (std::size_t i = StepBegin(k); i < step_end_[k]; ++i) {
    const Sample& s = step_samples_[i];
    if (!Covered(crack, s)) uncovered.push_back({s.point, s.edge, s.tet, s.at_surface});
  }
  return uncovered;
}

std::size_t FidelityMeter::crossed_tets() const {
  std::vector<std::uint32_t> tets;
  for (const Piece& p : pieces_) tets.push_back(p.tet);
  std::sort(tets.begin(), tets.end());
  return static_cast<std::size_t>(std::unique(tets.begin(), tets.end()) - tets.begin());
}

std::size_t FidelityMeter::fewest_samples_per_crossed_tet() const {
  absl::flat_hash_map<std::uint32_t, std::size_t> count;
  for (const Sample& s : Samples()) ++count[s.tet];
  std::size_t fewest = 0;
  for (const auto& [tet, n] : count) fewest = fewest == 0 ? n : std::min(fewest, n);
  return fewest;
}

}  // namespace kerf::lab
