#include "cli/chart_command.h"

#include <algorithm>
#include <fstream>

#include "absl/strings/str_cat.h"
#include "absl/strings/str_format.h"
#include "cli/command_args.h"
#include "cli/external_program.h"
#include "google/protobuf/util/json_util.h"
#include "kerf/v1/tradeoff_report.pb.h"
#include "mesh/io/mesh_file.h"

namespace kerf::cli {
namespace {

constexpr absl::string_view kChartUsage = "kerf chart TRADEOFF.json --out PREFIX";

// Marks by integrator (as they appear in TradeoffRow.integration), colours by law.
struct Series {
  const char* integration;
  const char* title;
  int point_type;  // gnuplot: 7 circle, 9 triangle, 5 square (filled)
};
constexpr Series kIntegrations[] = {{"SYMPLECTIC_EULER", "explicit", 7},
                                    {"SYMPLECTIC_EULER_SUBSTEPPED", "sub-stepped", 9},
                                    {"IMPLICIT_EULER", "backward Euler", 5}};
constexpr std::pair<const char*, const char*> kLaws[] = {{"linear", "#1f77b4"},
                                                         {"corotational", "#d62728"}};

// Writes LOAD.dat (cost, error, law, integration, n, default; the rows that did not blow up)
// and LOAD-front.dat (the Pareto front by cost) into `dir`; returns the panel's plot commands.
std::string Panel(const kerf::v1::TradeoffExperiment& experiment,
                  const kerf::v1::TradeoffReference& reference, const std::filesystem::path& dir,
                  bool with_key) {
  std::ofstream points(dir / absl::StrCat(reference.load(), ".dat"));
  std::vector<std::pair<double, double>> front;
  int blew_up = 0;
  for (const kerf::v1::TradeoffRow& row : experiment.rows()) {
    if (row.load() != reference.load()) continue;
    if (row.blew_up()) {
      ++blew_up;
      continue;
    }
    int law = 0, integration = 0;
    for (int i = 0; i < 2; ++i) law = row.law() == kLaws[i].first ? i : law;
    for (int i = 0; i < 3; ++i) {
      integration = row.integration() == kIntegrations[i].integration ? i : integration;
    }
    points << absl::StrFormat("%.6g %.6g %d %d %u %d\n", row.wall_seconds_per_simulated_second(),
                              row.relative_error(), law, integration, row.resolution(),
                              row.default_configuration() ? 1 : 0);
    if (row.pareto())
      front.emplace_back(row.wall_seconds_per_simulated_second(), row.relative_error());
  }
  std::sort(front.begin(), front.end());
  std::ofstream front_file(dir / absl::StrCat(reference.load(), "-front.dat"));
  for (const auto& [cost, error] : front) front_file << absl::StrFormat("%.6g %.6g\n", cost, error);

  const std::string data = absl::StrCat("'", reference.load(), ".dat'");
  std::string out =
      absl::StrFormat("set title \"%s: %s\\nagainst %s%s\"\n%s", reference.load(),
                      reference.quantity(), reference.solver(),
                      blew_up > 0 ? absl::StrCat("; ", blew_up, " runs blew up (not drawn)") : "",
                      with_key ? "set key bottom left box opaque font ',9' spacing 0.9 width -3\n"
                                 "set offsets 0, 0, 0, graph 0.5\n"
                               : "unset key\nset offsets 0, 0, 0, 0\n");
  absl::StrAppend(&out, "plot '", reference.load(),
                  "-front.dat' using 1:2 with lines dashtype 2 linewidth 2 linecolor rgb "
                  "'#777777' title 'Pareto front'");
  for (int law = 0; law < 2; ++law) {
    for (int i = 0; i < 3; ++i) {
      absl::StrAppendFormat(&out,
                            ", \\\n  %s using 1:(($3==%d && $4==%d) ? $2 : 1/0) with points "
                            "pointtype %d pointsize 1.4 linecolor rgb '%s' title '%s, %s'",
                            data, law, i, kIntegrations[i].point_type, kLaws[law].second,
                            kLaws[law].first, kIntegrations[i].title);
    }
  }
  absl::StrAppend(
      &out, ", \\\n  ", data,
      " using 1:($6==1 ? $2 : 1/0) with points pointtype 6 pointsize 3.2 linewidth 2 "
      "linecolor rgb 'black' title 'default: linear, backward Euler'",
      ", \\\n  ", data,
      " using 1:2:(sprintf('n=%d', $5)) with labels offset 1.6,0.7 font ',8' notitle\n");
  return out;
}

}  // namespace

absl::StatusOr<std::string> RunChartCommand(const std::vector<absl::string_view>& args) {
  CommandArgs rest(args);
  absl::StatusOr<std::optional<std::vector<absl::string_view>>> out = rest.TakeOption("--out", 1);
  if (!out.ok()) return out.status();
  absl::StatusOr<std::vector<absl::string_view>> files = rest.TakePositionals(1, kChartUsage);
  if (!files.ok()) return files.status();
  if (!out->has_value())
    return absl::InvalidArgumentError(absl::StrCat("--out is required: ", kChartUsage));
  absl::StatusOr<std::string> text = mesh::ReadTextFile((*files)[0]);
  if (!text.ok()) return text.status();
  kerf::v1::TradeoffExperiment experiment;
  if (const auto s = google::protobuf::util::JsonStringToMessage(*text, &experiment); !s.ok()) {
    return absl::InvalidArgumentError(absl::StrCat(
        (*files)[0], " is not the JSON of kerf experiment tradeoff: ", std::string(s.message())));
  }
  if (experiment.rows_size() == 0 || experiment.references_size() == 0) {
    return absl::InvalidArgumentError(absl::StrCat((*files)[0], " has no rows to draw"));
  }
  absl::StatusOr<TemporaryFolder> folder = TemporaryFolder::Create("kerf-chart");
  if (!folder.ok()) return folder.status();
  std::string panels = absl::StrFormat(
      "set termoption noenhanced\nset logscale xy\nset format xy '%%g'\nset grid\n"
      "set xlabel 'wall s per simulated s (this machine)'\n"
      "set ylabel 'relative error'\n"
      "set multiplot layout 1,%d title 'kerf: speed against accuracy (bars settled %g s, "
      "mass damping %g/s)'\n",
      experiment.references_size(), experiment.settle_seconds(), experiment.mass_damping());
  for (int i = 0; i < experiment.references_size(); ++i) {
    absl::StrAppend(&panels, Panel(experiment, experiment.references(i), folder->path(),
                                   i + 1 == experiment.references_size()));
  }
  absl::StrAppend(&panels, "unset multiplot\n");
  if ((**out)[0].find('\'') != absl::string_view::npos) {
    return absl::InvalidArgumentError(
        absl::StrCat("--out ", (**out)[0], ": a quote cannot stand in the prefix"));
  }
  const std::filesystem::path prefix = std::filesystem::absolute(std::string((**out)[0]));
  const std::string svg = prefix.string() + ".svg", png = prefix.string() + ".png";
  const int width = 560 * experiment.references_size();
  std::ofstream(folder->path() / "chart.gp") << absl::StrFormat(
      "set terminal svg size %d,600 dynamic font 'DejaVu Sans,12'\n"
      "set output '%s'\n%s"
      "set terminal pngcairo size %d,600 font 'DejaVu Sans,10'\n"
      "set output '%s'\n%s",
      width, svg, panels, width, png, panels);
  if (absl::Status s = RunExternalProgram("gnuplot", {"chart.gp"}, folder->path()); !s.ok()) {
    return s;
  }
  return absl::StrCat(svg, "\n", png, "\n");
}

}  // namespace kerf::cli
