// kerf: one binary, subcommands. Exit status 0 on success, 1 when the command failed (bad
// arguments, a bad input file, ...), 2 when no known command was given.
#include <iostream>
#include <vector>

#include "absl/status/statusor.h"
#include "absl/strings/string_view.h"
#include "cli/chart_command.h"
#include "cli/cut_command.h"
#include "cli/experiments/experiment_command.h"
#include "cli/mesh_commands.h"
#include "cli/path_command.h"
#include "cli/replay_command.h"
#include "cli/sim_command.h"
#include "cli/static_command.h"

namespace {

constexpr absl::string_view kKerfUsage =
    "usage: kerf demo [--json]\n"
    "       kerf mesh info FILE [--json]\n"
    "       kerf mesh lattice NX NY NZ [--size X Y Z] --out FILE\n"
    "       kerf mesh convert IN OUT\n"
    "       kerf sim run [SCENE] [--steps N] [--vtu-out DIR]\n"
    "       kerf sim list\n"
    "       kerf static DECK.inp [--json]\n"
    "       kerf cut MESH --path PATH.json --out OUT.vtu [--progressive|--deferred]\n"
    "                [--check every|end] [--uncovered OUT.csv] [--overcut OUT.csv]\n"
    "                [--lagging OUT.csv]\n"
    "                [--min-temporary-height F] [--snap F] [--trace OUT.jsonl]\n"
    "                [--dump-every-pose DIR] [--json]\n"
    "       kerf path hand|vertices|edges|face-plane MESH --out PATH.json [--seed N]\n"
    "                [--duration S] [--rate HZ]\n"
    "       kerf experiment lattice-cut|progressive-cases|live-cut [--json]\n"
    "       kerf experiment hand-cuts [--meshes FILE,...] [--seeds N] [--check every|end]\n"
    "                [--json]\n"
    "       kerf experiment tradeoff [--resolutions N,N,...] [--reference-resolution N]\n"
    "                [--seconds S] [--json]\n"
    "       kerf experiment stability [--liver FILE] [--scenes NAME,...] [--slow-down X]\n"
    "                [--json]\n"
    "       kerf chart TRADEOFF.json --out PREFIX\n"
    "       kerf replay JOURNAL [--speed X] [--listen HOST:PORT] [--export-at T,...|end]\n"
    "                   [--out-prefix P] [--linger S] [--json]\n";

}  // namespace

int main(int argc, char** argv) {
  const std::vector<absl::string_view> args(argv + 1, argv + argc);
  if (args.empty() || args[0] == "--help" || args[0] == "help") {
    std::cout << kKerfUsage;
    return args.empty() ? 2 : 0;
  }
  const std::vector<absl::string_view> rest(args.begin() + 1, args.end());
  absl::StatusOr<std::string> result;
  if (args[0] == "mesh") {
    result = kerf::cli::RunMeshCommand(rest);
  } else if (args[0] == "experiment") {
    result = kerf::cli::RunExperimentCommand(rest);
  } else if (args[0] == "cut") {
    result = kerf::cli::RunCutCommand(rest);
  } else if (args[0] == "path") {
    result = kerf::cli::RunPathCommand(rest);
  } else if (args[0] == "sim") {
    result = kerf::cli::RunSimCommand(rest);
  } else if (args[0] == "static") {
    result = kerf::cli::RunStaticCommand(rest);
  } else if (args[0] == "replay") {
    result = kerf::cli::RunReplayCommand(rest);
  } else if (args[0] == "chart") {
    result = kerf::cli::RunChartCommand(rest);
  } else if (args[0] == "demo") {
    result = kerf::cli::RunDemoCommand(rest);
  } else {
    std::cerr << "kerf: unknown command '" << args[0] << "'\n" << kKerfUsage;
    return 2;
  }
  if (!result.ok()) {
    std::cerr << "kerf: " << result.status().message() << "\n";
    return 1;
  }
  std::cout << *result;
  return 0;
}
