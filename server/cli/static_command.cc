#include "cli/static_command.h"

#include <algorithm>
#include <charconv>
#include <numeric>

#include "absl/strings/str_cat.h"
#include "cli/command_args.h"
#include "fem/static_solver.h"
#include "fem/tensor_mass_model.h"
#include "mesh/io/mesh_file.h"
#include "sim/abaqus_deck.h"

namespace kerf::cli {
namespace {

std::string Exact(double value) {
  char buffer[32];
  const auto [end, ec] = std::to_chars(buffer, buffer + sizeof(buffer), value);
  return std::string(buffer, end);
}

}  // namespace

absl::StatusOr<std::string> RunStaticCommand(const std::vector<absl::string_view>& args) {
  CommandArgs rest(args);
  const bool json = rest.TakeFlag("--json");
  absl::StatusOr<std::vector<absl::string_view>> files =
      rest.TakePositionals(1, "kerf static DECK.inp [--json]");
  if (!files.ok()) return files.status();
  absl::StatusOr<std::string> text = mesh::ReadTextFile((*files)[0]);
  if (!text.ok()) return text.status();
  absl::StatusOr<sim::StaticDeck> deck = sim::ParseStaticDeck(*text, (*files)[0]);
  if (!deck.ok()) return deck.status();
  absl::StatusOr<fem::TensorMassModel> model =
      fem::TensorMassModel::Create(deck->mesh, deck->material);
  if (!model.ok()) return model.status();
  absl::StatusOr<std::vector<Eigen::Vector3d>> u =
      fem::SolveStaticEquilibrium(*model, deck->conditions);
  if (!u.ok()) return u.status();

  std::vector<std::size_t> order(deck->node_ids.size());
  std::iota(order.begin(), order.end(), 0);
  std::sort(order.begin(), order.end(),
            [&](std::size_t a, std::size_t b) { return deck->node_ids[a] < deck->node_ids[b]; });
  std::string out = json ? "{\"displacements\": {" : "";
  for (std::size_t k = 0; k < order.size(); ++k) {
    const Eigen::Vector3d& d = (*u)[order[k]];
    const std::int64_t id = deck->node_ids[order[k]];
    if (json) {
      absl::StrAppend(&out, k ? ", " : "", "\"", id, "\": [", Exact(d.x()), ", ", Exact(d.y()),
                      ", ", Exact(d.z()), "]");
    } else {
      absl::StrAppend(&out, id, " ", Exact(d.x()), " ", Exact(d.y()), " ", Exact(d.z()), "\n");
    }
  }
  if (json) out += "}}\n";
  return out;
}

}  // namespace kerf::cli
