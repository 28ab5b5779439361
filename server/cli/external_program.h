// Running the external programs some commands use (CalculiX's ccx, gnuplot), each installed
// by scripts/setup, in a folder of their own.
#pragma once

#include <filesystem>
#include <string>
#include <vector>

#include "absl/status/statusor.h"
#include "absl/strings/string_view.h"

namespace kerf::cli {

// A new empty folder under the system's temporary folder, removed with everything in it when
// this object goes.
class TemporaryFolder {
 public:
  // INTERNAL if it cannot be made.
  static absl::StatusOr<TemporaryFolder> Create(absl::string_view prefix);
  TemporaryFolder(TemporaryFolder&& other) noexcept : path_(std::move(other.path_)) {
    other.path_.clear();
  }
  TemporaryFolder& operator=(TemporaryFolder&&) = delete;
  ~TemporaryFolder();
  const std::filesystem::path& path() const { return path_; }

 private:
  explicit TemporaryFolder(std::filesystem::path path) : path_(std::move(path)) {}
  std::filesystem::path path_;
};

// Runs `program` with `arguments` in folder `dir`, what it prints going to dir/<program>.log.
// FAILED_PRECONDITION naming the program if it is not on the PATH (scripts/setup installs
// it); INTERNAL with the log's last lines if it exits with a non-zero status.
absl::Status RunExternalProgram(absl::string_view program,
                                const std::vector<std::string>& arguments,
                                const std::filesystem::path& dir);

}  // namespace kerf::cli
