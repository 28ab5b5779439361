// kerf static DECK.inp [--json]: solves the static problem of a CalculiX/Abaqus deck with
// kerf's own stiffness and prints every node's displacement by its deck id.
#pragma once

#include <string>
#include <vector>

#include "absl/status/statusor.h"
#include "absl/strings/string_view.h"

namespace kerf::cli {

// --json prints {"displacements": {"<node id>": [ux, uy, uz], ...}} in deck id order, each
// number in its shortest exact form; without it, one line per node.
absl::StatusOr<std::string> RunStaticCommand(const std::vector<absl::string_view>& args);

}  // namespace kerf::cli
