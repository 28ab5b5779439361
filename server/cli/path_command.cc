#include "cli/path_command.h"

#include "absl/strings/str_cat.h"
#include "cli/command_args.h"
#include "cli/cut_command.h"
#include "lab/hand_paths.h"
#include "mesh/io/mesh_file.h"

namespace kerf::cli {
namespace {

constexpr absl::string_view kPathUsage =
    "kerf path hand|vertices|edges|face-plane MESH --out PATH.json [--seed N] [--duration S] "
    "[--rate HZ]";

}  // namespace

absl::StatusOr<std::string> RunPathCommand(const std::vector<absl::string_view>& args) {
  CommandArgs rest(args);
  lab::HandPathOptions options;
  int seed = 1;
  absl::StatusOr<std::optional<std::vector<absl::string_view>>> out = rest.TakeOption("--out", 1);
  if (!out.ok()) return out.status();
  absl::StatusOr<std::optional<std::vector<absl::string_view>>> seed_arg =
      rest.TakeOption("--seed", 1);
  if (!seed_arg.ok()) return seed_arg.status();
  if (seed_arg->has_value()) {
    absl::StatusOr<int> parsed = ParseIntArg((**seed_arg)[0], "--seed");
    if (!parsed.ok()) return parsed.status();
    seed = *parsed;
  }
  for (auto [flag, into] : {std::pair<absl::string_view, double*>{"--duration", &options.duration},
                            {"--rate", &options.rate}}) {
    absl::StatusOr<std::optional<std::vector<absl::string_view>>> value = rest.TakeOption(flag, 1);
    if (!value.ok()) return value.status();
    if (!value->has_value()) continue;
    absl::StatusOr<double> parsed = ParseDoubleArg((**value)[0], flag);
    if (!parsed.ok()) return parsed.status();
    if (!(*parsed > 0)) return absl::InvalidArgumentError(absl::StrCat(flag, " must be positive"));
    *into = *parsed;
  }
  absl::StatusOr<std::vector<absl::string_view>> positionals = rest.TakePositionals(2, kPathUsage);
  if (!positionals.ok()) return positionals.status();
  if (!out->has_value()) {
    return absl::InvalidArgumentError(absl::StrCat("--out is required\nusage: ", kPathUsage));
  }
  absl::StatusOr<lab::PathFamily> family = lab::ParsePathFamily((*positionals)[0]);
  if (!family.ok()) return family.status();
  absl::StatusOr<mesh::TetMesh> m = LoadMeshOrScene((*positionals)[1]);
  if (!m.ok()) return m.status();
  if (m->tet_count() == 0) {
    return absl::InvalidArgumentError(absl::StrCat((*positionals)[1], " has no tets"));
  }
  const std::vector<cut::BladePose> poses =
      lab::MakeHandPath(*m, *family, static_cast<std::uint64_t>(seed), options);
  absl::Status written = mesh::WriteTextFile((**out)[0], lab::FormatBladePathJson(poses));
  if (!written.ok()) return written;
  return absl::StrCat(lab::PathFamilyName(*family), " path, seed ", seed, ": ", poses.size(),
                      " poses over ", poses.back().time, " s; wrote ", (**out)[0], "\n");
}

}  // namespace kerf::cli
