// kerf replay JOURNAL [--speed X] [--listen HOST:PORT] [--export-at T,T,...|end]
//                     [--out-prefix P] [--linger S] [--json]
//
// Replays a recorded session (a journal of kerf-server's --journal_dir) into a new session that
// observers can watch over gRPC while it runs (the address, session id and observer token are
// printed first; --listen= serves nothing), at `speed` simulated seconds per wall-clock second
// (default 1). The replay is deterministic: it rebuilds the recorded model bit for bit, so
// it can also export the mesh at any simulated time T (s) as P-tT.vtu (current positions, and
// rest_position per point), with the model's SHA-256 in the report. It ends at the recording's
// last event or the last export time, whichever is later, plus --linger seconds.
#pragma once

#include <string>
#include <vector>

#include "absl/status/statusor.h"
#include "absl/strings/string_view.h"

namespace kerf::cli {

absl::StatusOr<std::string> RunReplayCommand(const std::vector<absl::string_view>& args);

}  // namespace kerf::cli
