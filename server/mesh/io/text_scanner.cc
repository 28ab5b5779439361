#include "mesh/io/text_scanner.h"

#include <algorithm>
#include <charconv>
#include <cmath>

#include "absl/strings/str_cat.h"

namespace kerf::mesh::internal {
namespace {

bool IsSpace(char c) {
  return c == ' ' || c == '\t' || c == '\n' || c == '\r' || c == '\v' || c == '\f';
}

absl::string_view StripPlus(absl::string_view token) {
  if (token.size() > 1 && token[0] == '+') token.remove_prefix(1);
  return token;
}

}  // namespace

bool ParseInt(absl::string_view token, std::int64_t* value) {
  token = StripPlus(token);
  const char* end = token.data() + token.size();
  const auto [ptr, ec] = std::from_chars(token.data(), end, *value);
  return ec == std::errc() && ptr == end && !token.empty();
}

bool ParseDouble(absl::string_view token, double* value) {
  token = StripPlus(token);
  const char* end = token.data() + token.size();
  const auto [ptr, ec] = std::from_chars(token.data(), end, *value);
  return ec == std::errc() && ptr == end && !token.empty();
}

std::string Quoted(absl::string_view token) {
  if (token.empty()) return "end of file";
  constexpr std::size_t kMax = 40;
  std::string shown(token.substr(0, kMax));
  for (char& c : shown) {
    if (static_cast<unsigned char>(c) < 0x20 || static_cast<unsigned char>(c) > 0x7e) c = '?';
  }
  return absl::StrCat("'", shown, token.size() > kMax ? "...'" : "'");
}

void TextScanner::SkipSpaceAndComments() {
  while (pos_ < text_.size()) {
    const char c = text_[pos_];
    if (IsSpace(c)) {
      ++pos_;
    } else if (comment_ != '\0' && c == comment_) {
      while (pos_ < text_.size() && text_[pos_] != '\n') ++pos_;
    } else {
      break;
    }
  }
}

absl::string_view TextScanner::PeekToken() {
  SkipSpaceAndComments();
  std::size_t end = pos_;
  while (end < text_.size() && !IsSpace(text_[end]) && text_[end] != comment_) ++end;
  return text_.substr(pos_, end - pos_);
}

absl::string_view TextScanner::NextToken() {
  const absl::string_view token = PeekToken();
  token_start_ = pos_;
  token_ = token;
  pos_ += token.size();
  return token;
}

absl::string_view TextScanner::NextLine() {
  std::size_t end = pos_;
  while (end < text_.size() && text_[end] != '\n') ++end;
  absl::string_view line = text_.substr(pos_, end - pos_);
  if (!line.empty() && line.back() == '\r') line.remove_suffix(1);
  token_start_ = pos_;
  token_ = line;
  pos_ = std::min(end + 1, text_.size());
  return line;
}

bool TextScanner::AtEnd() {
  SkipSpaceAndComments();
  return pos_ >= text_.size();
}

absl::StatusOr<std::int64_t> TextScanner::NextInt(absl::string_view what) {
  std::int64_t value = 0;
  if (!ParseInt(NextToken(), &value)) return ErrorExpected(absl::StrCat(what, " (an integer)"));
  return value;
}

absl::StatusOr<std::int64_t> TextScanner::NextIntIn(absl::string_view what, std::int64_t low,
                                                    std::int64_t high) {
  std::int64_t value = 0;
  if (!ParseInt(NextToken(), &value) || value < low || value > high) {
    return ErrorExpected(absl::StrCat(what, " (an integer in [", low, ", ", high, "])"));
  }
  return value;
}

absl::StatusOr<double> TextScanner::NextFiniteDouble(absl::string_view what) {
  double value = 0;
  if (!ParseDouble(NextToken(), &value) || !std::isfinite(value)) {
    return ErrorExpected(absl::StrCat(what, " (a finite number)"));
  }
  return value;
}

absl::Status TextScanner::Expect(absl::string_view expected) {
  if (NextToken() != expected) return ErrorExpected(absl::StrCat("'", expected, "'"));
  return absl::OkStatus();
}

int TextScanner::LineAt(std::size_t offset) const {
  offset = std::min(offset, text_.size());
  return 1 + static_cast<int>(std::count(
                 text_.begin(), text_.begin() + static_cast<std::ptrdiff_t>(offset), '\n'));
}

absl::Status TextScanner::ErrorExpected(absl::string_view expected) const {
  return ErrorAt(token_start_, absl::StrCat("expected ", expected, ", found ", Quoted(token_)));
}

absl::Status TextScanner::Error(absl::string_view message) const {
  return ErrorAt(token_start_, message);
}

absl::Status TextScanner::ErrorAt(std::size_t offset, absl::string_view message) const {
  return absl::InvalidArgumentError(absl::StrCat(source_, ":", LineAt(offset), ": ", message));
}

}  // namespace kerf::mesh::internal
