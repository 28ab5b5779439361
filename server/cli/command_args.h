// The arguments of one kerf subcommand: positional values and --options, taken one by one so
// that anything left over is reported as unknown.
#pragma once

#include <initializer_list>
#include <optional>
#include <vector>

#include "absl/status/statusor.h"
#include "absl/strings/string_view.h"

namespace kerf::cli {

class CommandArgs {
 public:
  explicit CommandArgs(std::vector<absl::string_view> args) : args_(std::move(args)) {}

  // True if --name was given (and removes it).
  bool TakeFlag(absl::string_view name);

  // The `count` values after --name (and removes them all), or nullopt if --name is absent.
  // INVALID_ARGUMENT if fewer than `count` values follow.
  absl::StatusOr<std::optional<std::vector<absl::string_view>>> TakeOption(absl::string_view name,
                                                                           int count);

  // The value after --name (and removes both), or nullopt if --name is absent. INVALID_ARGUMENT
  // "--name takes a or b, not "x"" with `usage` for a value not among `choices`.
  absl::StatusOr<std::optional<absl::string_view>> TakeChoice(
      absl::string_view name, std::initializer_list<absl::string_view> choices,
      absl::string_view usage);

  // The remaining arguments, which must be exactly `count` positional values.
  // INVALID_ARGUMENT naming an unknown option or the wrong count, with `usage`.
  absl::StatusOr<std::vector<absl::string_view>> TakePositionals(std::size_t count,
                                                                 absl::string_view usage);

 private:
  std::vector<absl::string_view> args_;
};

// Parses a whole argument as a number; INVALID_ARGUMENT naming `what` otherwise.
absl::StatusOr<int> ParseIntArg(absl::string_view value, absl::string_view what);
absl::StatusOr<double> ParseDoubleArg(absl::string_view value, absl::string_view what);

}  // namespace kerf::cli
