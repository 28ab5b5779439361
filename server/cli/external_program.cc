#include "cli/external_program.h"

#include <sys/wait.h>

#include <cstdlib>
#include <fstream>
#include <sstream>

#include "absl/strings/str_cat.h"
#include "absl/strings/str_replace.h"

namespace kerf::cli {
namespace {

// `text` in single quotes for /bin/sh.
std::string ShellQuoted(absl::string_view text) {
  return absl::StrCat("'", absl::StrReplaceAll(text, {{"'", "'\\''"}}), "'");
}

std::string LastLines(const std::filesystem::path& file, int count) {
  std::ifstream in(file);
  std::vector<std::string> lines;
  for (std::string line; std::getline(in, line);) {
    if (!line.empty()) lines.push_back(line);
  }
  std::string out;
  for (std::size_t i = lines.size() > static_cast<std::size_t>(count) ? lines.size() - count : 0;
       i < lines.size(); ++i) {
    absl::StrAppend(&out, "\n  ", lines[i]);
  }
  return out;
}

}  // namespace

absl::StatusOr<TemporaryFolder> TemporaryFolder::Create(absl::string_view prefix) {
  std::string pattern =
      (std::filesystem::temp_directory_path() / absl::StrCat(prefix, "-XXXXXX")).string();
  if (mkdtemp(pattern.data()) == nullptr) {
    return absl::InternalError(absl::StrCat("cannot make a temporary folder ", pattern));
  }
  return TemporaryFolder(pattern);
}

TemporaryFolder::~TemporaryFolder() {
  if (path_.empty()) return;
  std::error_code ignored;
  std::filesystem::remove_all(path_, ignored);
}

absl::Status RunExternalProgram(absl::string_view program,
                                const std::vector<std::string>& arguments,
                                const std::filesystem::path& dir) {
  const std::string name(program);
  if (std::system(absl::StrCat("command -v ", ShellQuoted(name), " > /dev/null 2>&1").c_str()) !=
      0) {
    return absl::FailedPreconditionError(
        absl::StrCat(name, " is not installed (scripts/setup installs it)"));
  }
  const std::filesystem::path log = dir / absl::StrCat(name, ".log");
  std::string command = absl::StrCat("cd ", ShellQuoted(dir.string()), " && ", ShellQuoted(name));
  for (const std::string& argument : arguments)
    absl::StrAppend(&command, " ", ShellQuoted(argument));
  absl::StrAppend(&command, " < /dev/null > ", ShellQuoted(log.string()), " 2>&1");
  const int status = std::system(command.c_str());
  if (status != 0) {
    return absl::InternalError(absl::StrCat(name, " failed (exit status ",
                                            WIFEXITED(status) ? WEXITSTATUS(status) : -1,
                                            "); the end of its output:", LastLines(log, 8)));
  }
  return absl::OkStatus();
}

}  // namespace kerf::cli
