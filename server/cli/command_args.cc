#include "cli/command_args.h"

#include <algorithm>
#include <charconv>
#include <cmath>

#include "absl/strings/match.h"
#include "absl/strings/str_cat.h"
#include "absl/strings/str_join.h"

namespace kerf::cli {

bool CommandArgs::TakeFlag(absl::string_view name) {
  const auto it = std::find(args_.begin(), args_.end(), name);
  if (it == args_.end()) return false;
  args_.erase(it);
  return true;
}

absl::StatusOr<std::optional<std::vector<absl::string_view>>> CommandArgs::TakeOption(
    absl::string_view name, int count) {
  const auto it = std::find(args_.begin(), args_.end(), name);
  if (it == args_.end()) return std::nullopt;
  const bool enough =
      args_.end() - it > count && std::none_of(it + 1, it + 1 + count, [](absl::string_view value) {
        return absl::StartsWith(value, "--");
      });
  if (!enough) {
    return absl::InvalidArgumentError(absl::StrCat(name, " needs ", count, " value(s)"));
  }
  std::vector<absl::string_view> values(it + 1, it + 1 + count);
  args_.erase(it, it + 1 + count);
  return values;
}

absl::StatusOr<std::optional<absl::string_view>> CommandArgs::TakeChoice(
    absl::string_view name, std::initializer_list<absl::string_view> choices,
    absl::string_view usage) {
  absl::StatusOr<std::optional<std::vector<absl::string_view>>> value = TakeOption(name, 1);
  if (!value.ok()) return value.status();
  if (!value->has_value()) return std::nullopt;
  const absl::string_view chosen = (**value)[0];
  if (std::find(choices.begin(), choices.end(), chosen) != choices.end()) return chosen;
  return absl::InvalidArgumentError(absl::StrCat(name, " takes ", absl::StrJoin(choices, " or "),
                                                 ", not \"", chosen, "\"\nusage: ", usage));
}

absl::StatusOr<std::vector<absl::string_view>> CommandArgs::TakePositionals(
    std::size_t count, absl::string_view usage) {
  for (const absl::string_view arg : args_) {
    if (absl::StartsWith(arg, "--")) {
      return absl::InvalidArgumentError(absl::StrCat("unknown option ", arg, "\nusage: ", usage));
    }
  }
  if (args_.size() != count) {
    return absl::InvalidArgumentError(
        absl::StrCat("expected ", count, " argument(s), got ", args_.size(), "\nusage: ", usage));
  }
  return args_;
}

absl::StatusOr<int> ParseIntArg(absl::string_view value, absl::string_view what) {
  int result = 0;
  const auto [end, ec] = std::from_chars(value.data(), value.data() + value.size(), result);
  if (ec != std::errc() || end != value.data() + value.size() || value.empty()) {
    return absl::InvalidArgumentError(absl::StrCat(what, " must be an integer, got '", value, "'"));
  }
  return result;
}

absl::StatusOr<double> ParseDoubleArg(absl::string_view value, absl::string_view what) {
  double result = 0;
  const auto [end, ec] = std::from_chars(value.data(), value.data() + value.size(), result);
  if (ec != std::errc() || end != value.data() + value.size() || value.empty() ||
      !std::isfinite(result)) {
    return absl::InvalidArgumentError(
        absl::StrCat(what, " must be a finite number, got '", value, "'"));
  }
  return result;
}

}  // namespace kerf::cli
