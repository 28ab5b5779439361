#include "cli/sim_command.h"

#include <chrono>
#include <filesystem>

#include "absl/strings/str_cat.h"
#include "absl/strings/str_format.h"
#include "cli/command_args.h"
#include "fem/explicit_integrator.h"
#include "mesh/io/mesh_file.h"
#include "mesh/io/vtu_writer.h"
#include "sim/simulation.h"

namespace kerf::cli {
namespace {

constexpr absl::string_view kSimUsage =
    "kerf sim run [SCENE] [--steps N] [--vtu-out DIR] | kerf sim list";
constexpr absl::string_view kDefaultScene = "lattice-tension";

absl::Status WriteFrame(const sim::Simulation& simulation, const std::string& path) {
  mesh::VtuExtraArrays extra;
  std::vector<double> displacement;
  for (const mesh::VertexId v : simulation.mesh().vertices()) {
    const Eigen::Vector3d& d = simulation.state().displacement[mesh::Index(v)];
    displacement.insert(displacement.end(), {d.x(), d.y(), d.z()});
  }
  extra.point_data.push_back({"displacement", 3, std::move(displacement)});
  return mesh::WriteTextFile(path, mesh::FormatVtu(simulation.mesh(), extra));
}

absl::StatusOr<std::string> Run(CommandArgs args) {
  absl::StatusOr<std::optional<std::vector<absl::string_view>>> steps_arg =
      args.TakeOption("--steps", 1);
  if (!steps_arg.ok()) return steps_arg.status();
  absl::StatusOr<std::optional<std::vector<absl::string_view>>> out_arg =
      args.TakeOption("--vtu-out", 1);
  if (!out_arg.ok()) return out_arg.status();
  absl::StatusOr<std::vector<absl::string_view>> scene_arg = args.TakePositionals(1, kSimUsage);
  if (!scene_arg.ok()) {
    scene_arg = args.TakePositionals(0, kSimUsage);
    if (!scene_arg.ok()) return scene_arg.status();
    scene_arg->push_back(kDefaultScene);
  }
  int steps = 1000;
  if (steps_arg->has_value()) {
    absl::StatusOr<int> n = ParseIntArg((**steps_arg)[0], "--steps");
    if (!n.ok()) return n.status();
    if (*n < 0) return absl::InvalidArgumentError(absl::StrCat("--steps must be >= 0, got ", *n));
    steps = *n;
  }
  absl::StatusOr<sim::Scene> scene = sim::LoadScene((*scene_arg)[0]);
  if (!scene.ok()) return scene.status();
  const std::string name = scene->name;
  const bool dynamic = scene->method != kerf::v1::Integration::STATIC;
  const std::string method = kerf::v1::Integration::Method_Name(scene->method);
  absl::StatusOr<std::unique_ptr<sim::Simulation>> simulation =
      sim::Simulation::Create(*std::move(scene));
  if (!simulation.ok()) return simulation.status();
  sim::Simulation& s = **simulation;

  std::string folder;
  std::string collection;
  int frames = 0;
  const int frame_every = std::max(1, steps / 100);
  auto write_frame = [&]() -> absl::Status {
    if (folder.empty()) return absl::OkStatus();
    const std::string file = absl::StrFormat("frame_%06d.vtu", frames++);
    absl::StrAppendFormat(&collection, "    <DataSet timestep=\"%.9g\" file=\"%s\"/>\n",
                          s.state().time, file);
    return WriteFrame(s, (std::filesystem::path(folder) / file).string());
  };
  if (out_arg->has_value()) {
    folder = std::string((**out_arg)[0]);
    std::error_code error;
    std::filesystem::create_directories(folder, error);
    if (error) {
      return absl::PermissionDeniedError(absl::StrCat(folder, ": ", error.message()));
    }
    if (absl::Status st = write_frame(); !st.ok()) return st;
  }

  const auto start = std::chrono::steady_clock::now();
  for (int step = 1; step <= steps; ++step) {
    s.Step();
    if (step % frame_every == 0 || step == steps) {
      if (absl::Status st = write_frame(); !st.ok()) return st;
    }
  }
  const double wall =
      std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();

  double max_displacement = 0;
  for (const mesh::VertexId v : s.mesh().vertices()) {
    max_displacement = std::max(max_displacement, s.state().displacement[mesh::Index(v)].norm());
  }
  std::string out = absl::StrFormat("scene %s: %d vertices, %d tets, %s\n", name,
                                    s.mesh().vertex_count(), s.mesh().tet_count(), method);
  if (dynamic) {
    absl::StrAppendFormat(&out, "  time step %.4g s (critical step %.4g s)\n", s.time_step(),
                          s.critical_time_step());
    absl::StrAppendFormat(&out, "  %d steps: %.6g s simulated in %.3g s wall (%.0f steps/s)\n",
                          steps, s.state().time, wall, wall > 0 ? steps / wall : 0.0);
  }
  absl::StrAppendFormat(&out, "  max displacement %.6g, mechanical energy %.6g\n", max_displacement,
                        s.MechanicalEnergy());
  if (!folder.empty()) {
    const std::string pvd = (std::filesystem::path(folder) / (name + ".pvd")).string();
    if (absl::Status st = mesh::WriteTextFile(
            pvd, absl::StrCat("<?xml version=\"1.0\"?>\n<VTKFile type=\"Collection\" "
                              "version=\"0.1\">\n  <Collection>\n",
                              collection, "  </Collection>\n</VTKFile>\n"));
        !st.ok()) {
      return st;
    }
    absl::StrAppendFormat(&out, "  wrote %d VTU frames and %s\n", frames, pvd);
  }
  return out;
}

}  // namespace

absl::StatusOr<std::string> RunSimCommand(const std::vector<absl::string_view>& args) {
  if (!args.empty() && args[0] == "run") return Run(CommandArgs({args.begin() + 1, args.end()}));
  if (!args.empty() && args[0] == "list") {
    std::string out;
    for (const std::string& name : sim::EmbeddedSceneNames()) {
      absl::StatusOr<kerf::v1::Scene> scene =
          sim::ParseSceneText(*sim::EmbeddedSceneText(name), name);
      absl::StrAppend(&out, name, ": ", scene.ok() ? scene->description() : "(unreadable)", "\n");
    }
    return out;
  }
  return absl::InvalidArgumentError(absl::StrCat("usage: ", kSimUsage));
}

}  // namespace kerf::cli
