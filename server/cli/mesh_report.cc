#include "cli/mesh_report.h"

#include "absl/strings/str_cat.h"
#include "absl/strings/str_format.h"
#include "cli/json_output.h"
#include "mesh/boundary_surface.h"
#include "mesh/connected_components.h"
#include "mesh/mesh_quality.h"
#include "mesh/mesh_validation.h"

namespace kerf::cli {
namespace {

void SetVector(const Eigen::Vector3d& from, kerf::v1::Vector3* to) {
  to->set_x(from.x());
  to->set_y(from.y());
  to->set_z(from.z());
}

}  // namespace

kerf::v1::MeshReport MakeMeshReport(const mesh::TetMesh& mesh, absl::string_view source) {
  kerf::v1::MeshReport report;
  report.set_source(std::string(source));
  report.set_vertices(static_cast<std::uint32_t>(mesh.vertex_count()));
  report.set_tets(static_cast<std::uint32_t>(mesh.tet_count()));
  report.set_boundary_triangles(
      static_cast<std::uint32_t>(mesh::ExtractBoundarySurface(mesh).size()));
  report.set_components(static_cast<std::uint32_t>(mesh::FindConnectedComponents(mesh).count));

  const std::vector<mesh::MeshDefect> defects = mesh::FindMeshDefects(mesh);
  report.set_valid(defects.empty());
  report.set_defect_count(static_cast<std::uint32_t>(defects.size()));
  constexpr std::size_t kShownDefects = 10;
  for (std::size_t i = 0; i < std::min(defects.size(), kShownDefects); ++i) {
    report.add_defects(defects[i].message);
  }

  const mesh::Bounds bounds = mesh::MeasureBounds(mesh);
  SetVector(bounds.low, report.mutable_bounding_box()->mutable_min());
  SetVector(bounds.high, report.mutable_bounding_box()->mutable_max());

  const mesh::MeshQuality quality = mesh::MeasureMeshQuality(mesh);
  report.set_volume(quality.total_volume);
  report.set_min_dihedral_deg(quality.min_dihedral_deg);
  report.set_max_dihedral_deg(quality.max_dihedral_deg);
  report.set_min_radius_ratio(quality.min_radius_ratio);
  report.set_mean_radius_ratio(quality.mean_radius_ratio);
  report.set_min_edge_length(quality.min_edge_length);
  report.set_max_edge_length(quality.max_edge_length);
  report.set_min_tet_volume(quality.min_volume);
  report.set_slivers(static_cast<std::uint32_t>(quality.slivers));
  report.set_sliver_angle_deg(mesh::kDefaultSliverAngleDeg);
  for (std::size_t bin = 0; bin < quality.min_dihedral_histogram.size(); ++bin) {
    kerf::v1::DihedralHistogramBin* out = report.add_min_dihedral_histogram();
    out->set_from_deg(10.0 * static_cast<double>(bin));
    out->set_to_deg(10.0 * static_cast<double>(bin + 1));
    out->set_tets(static_cast<std::uint32_t>(quality.min_dihedral_histogram[bin]));
  }
  return report;
}

std::string FormatMeshReportText(const kerf::v1::MeshReport& r) {
  std::string out = absl::StrFormat(
      "%s\n  vertices %u, tets %u, boundary triangles %u, components %u\n"
      "  valid: %s",
      r.source(), r.vertices(), r.tets(), r.boundary_triangles(), r.components(),
      r.valid() ? "yes" : absl::StrCat("no, ", r.defect_count(), " defect(s)"));
  for (const std::string& defect : r.defects()) absl::StrAppend(&out, "\n    ", defect);
  const auto& lo = r.bounding_box().min();
  const auto& hi = r.bounding_box().max();
  absl::StrAppendFormat(&out,
                        "\n  bounding box [%g, %g, %g] - [%g, %g, %g], volume %g\n"
                        "  dihedral angles %.2f - %.2f deg, radius ratio min %.3f mean %.3f\n"
                        "  edge lengths %g - %g, slivers (under %g deg) %u\n"
                        "  tets by smallest dihedral angle:",
                        lo.x(), lo.y(), lo.z(), hi.x(), hi.y(), hi.z(), r.volume(),
                        r.min_dihedral_deg(), r.max_dihedral_deg(), r.min_radius_ratio(),
                        r.mean_radius_ratio(), r.min_edge_length(), r.max_edge_length(),
                        r.sliver_angle_deg(), r.slivers());
  for (const auto& bin : r.min_dihedral_histogram()) {
    absl::StrAppendFormat(&out, "\n    %2.0f-%2.0f deg %8u", bin.from_deg(), bin.to_deg(),
                          bin.tets());
  }
  out += '\n';
  return out;
}

std::string FormatMeshReportJson(const kerf::v1::MeshReport& report) {
  return FormatProtoJson(report);
}

}  // namespace kerf::cli
