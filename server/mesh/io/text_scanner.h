// Reads whitespace-separated tokens from text in memory, knowing where it is, so that every
// parse error names the source, the line and what was expected:
//   "liver.msh:12: expected node count (an integer), found 'abc'".
// Never reads past the end of the text; an exhausted scanner returns empty tokens.
#pragma once

#include <cstdint>
#include <string>

#include "absl/status/status.h"
#include "absl/status/statusor.h"
#include "absl/strings/string_view.h"

namespace kerf::mesh::internal {

// The most items (points, cells, blocks) a mesh file may declare: far above any mesh kerf can
// hold, and low enough that a count read from a damaged file cannot overflow a size computed
// from it.
inline constexpr std::int64_t kMaxItemCount = std::int64_t{1} << 40;

class TextScanner {
 public:
  // `comment` starts a comment that runs to the end of the line ('\0': no comments).
  TextScanner(absl::string_view text, absl::string_view source, char comment = '\0')
      : text_(text), source_(source), comment_(comment) {}

  // The next token, or empty at the end of the text.
  absl::string_view NextToken();
  absl::string_view PeekToken();

  // The rest of the current line (after a token was read) or the next line (at a line
  // start), without its end-of-line characters; advances past it.
  absl::string_view NextLine();

  // Numbers: `what` names the value for the error message.
  absl::StatusOr<std::int64_t> NextInt(absl::string_view what);
  absl::StatusOr<double> NextFiniteDouble(absl::string_view what);
  // An integer in [low, high].
  absl::StatusOr<std::int64_t> NextIntIn(absl::string_view what, std::int64_t low,
                                         std::int64_t high);

  // Consumes the next token if it equals `expected`, else an error naming both.
  absl::Status Expect(absl::string_view expected);

  bool AtEnd();

  // "source:line: expected <expected>, found '<token>'" at the last token read.
  absl::Status ErrorExpected(absl::string_view expected) const;
  // "source:line: <message>" at the last token read, or at a given offset.
  absl::Status Error(absl::string_view message) const;
  absl::Status ErrorAt(std::size_t offset, absl::string_view message) const;

  std::size_t offset() const { return pos_; }
  // Where the last token (or line) read starts.
  std::size_t token_offset() const { return token_start_; }
  absl::string_view source() const { return source_; }
  absl::string_view text() const { return text_; }
  // 1-based line number of a byte offset. O(offset).
  int LineAt(std::size_t offset) const;

 private:
  void SkipSpaceAndComments();

  absl::string_view text_;
  absl::string_view source_;
  char comment_;
  std::size_t pos_ = 0;
  std::size_t token_start_ = 0;
  absl::string_view token_;
};

// Parses a whole token as a number (no sign other than a leading '-' or '+').
bool ParseInt(absl::string_view token, std::int64_t* value);
bool ParseDouble(absl::string_view token, double* value);

// A token for an error message: shortened, with "end of file" for the empty token.
std::string Quoted(absl::string_view token);

}  // namespace kerf::mesh::internal
