#include "cli/experiments/tradeoff_experiment.h"

#include <cmath>
#include <limits>

#include "absl/strings/str_cat.h"
#include "absl/strings/str_format.h"
#include "cli/experiments/calculix_reference.h"
#include "lab/accuracy_bar.h"

namespace kerf::cli {
namespace {

constexpr kerf::v1::Integration::Method kMethods[] = {
    kerf::v1::Integration::SYMPLECTIC_EULER, kerf::v1::Integration::SYMPLECTIC_EULER_SUBSTEPPED,
    kerf::v1::Integration::IMPLICIT_EULER};
constexpr double kSameError = 1e-3;  // relative
constexpr fem::ElasticLaw kLaws[] = {fem::ElasticLaw::kLinear, fem::ElasticLaw::kCorotational};

std::string QuantityName(lab::BarLoad load) {
  switch (load) {
    case lab::BarLoad::kCantilever:
      return "displacement of the tip-face centre (5, 0.5, 0.5)";
    case lab::BarLoad::kTension:
      return "force holding the pulled face x = 5";
    case lab::BarLoad::kTwist:
      return "displacement of the mid-length corner (2.5, 1, 1)";
  }
  return "";
}

// a is as cheap as b and as accurate (errors within kSameError of each other count as equal:
// rows that settle to the same answer differ by what settling leaves), and better in one.
bool Dominates(const kerf::v1::TradeoffRow& a, const kerf::v1::TradeoffRow& b) {
  const double cost_a = a.wall_seconds_per_simulated_second();
  const double cost_b = b.wall_seconds_per_simulated_second();
  const bool same_error =
      std::abs(a.relative_error() - b.relative_error()) <= kSameError * b.relative_error();
  const bool as_accurate = same_error || a.relative_error() < b.relative_error();
  return cost_a <= cost_b && as_accurate && (cost_a < cost_b || !same_error);
}

}  // namespace

void MarkParetoFront(kerf::v1::TradeoffExperiment* experiment) {
  for (kerf::v1::TradeoffRow& row : *experiment->mutable_rows()) {
    bool dominated = row.blew_up();
    for (const kerf::v1::TradeoffRow& other : experiment->rows()) {
      if (dominated) break;
      dominated =
          &other != &row && !other.blew_up() && other.load() == row.load() && Dominates(other, row);
    }
    row.set_pareto(!dominated);
  }
}

absl::StatusOr<kerf::v1::TradeoffExperiment> RunTradeoff(const TradeoffOptions& options) {
  for (const int n : options.resolutions) {
    if (absl::Status s = lab::CheckBarResolution(n); !s.ok()) return s;
  }
  if (absl::Status s = lab::CheckBarResolution(options.reference_resolution); !s.ok()) return s;
  kerf::v1::TradeoffExperiment experiment;
  experiment.set_settle_seconds(options.settle_seconds);
  experiment.set_mass_damping(options.mass_damping);
  for (const lab::BarLoad load : lab::kBarLoads) {
    absl::StatusOr<Eigen::Vector3d> reference =
        CalculixReference(load, options.reference_resolution);
    if (!reference.ok()) return reference.status();
    kerf::v1::TradeoffReference& r = *experiment.add_references();
    r.set_load(lab::BarLoadName(load));
    r.set_quantity(QuantityName(load));
    r.set_solver(absl::StrCat("CalculiX C3D10, n = ", options.reference_resolution,
                              load == lab::BarLoad::kTwist ? ", NLGEOM" : ", linear"));
    r.mutable_value()->Add(reference->data(), reference->data() + 3);
    for (const int n : options.resolutions) {
      for (const fem::ElasticLaw law : kLaws) {
        for (const kerf::v1::Integration::Method method : kMethods) {
          absl::StatusOr<lab::BarSettleResult> run =
              lab::SettleBar(load, n, method, law, options.mass_damping, options.settle_seconds);
          if (!run.ok()) return run.status();
          kerf::v1::TradeoffRow& row = *experiment.add_rows();
          row.set_load(lab::BarLoadName(load));
          row.set_resolution(n);
          row.set_tets(6 * 5 * n * n * n);
          row.set_law(law == fem::ElasticLaw::kLinear ? "linear" : "corotational");
          row.set_integration(kerf::v1::Integration::Method_Name(method));
          row.set_time_step(run->time_step);
          row.set_steps(run->steps);
          row.set_wall_seconds_per_simulated_second(run->wall_seconds / run->simulated_seconds);
          row.mutable_value()->Add(run->quantity.data(), run->quantity.data() + 3);
          row.set_blew_up(!run->finite);
          row.set_relative_error(run->finite
                                     ? (run->quantity - *reference).norm() / reference->norm()
                                     : std::numeric_limits<double>::infinity());
          row.set_default_configuration(method == kerf::v1::Integration::IMPLICIT_EULER &&
                                        law == fem::ElasticLaw::kLinear);
        }
      }
    }
  }
  MarkParetoFront(&experiment);
  return experiment;
}

std::string FormatTradeoff(const kerf::v1::TradeoffExperiment& experiment) {
  std::string out = absl::StrFormat(
      "tradeoff: each bar settles %g s (mass damping %g/s) from a start near its answer; "
      "error = |value - reference| / |reference|\n",
      experiment.settle_seconds(), experiment.mass_damping());
  for (const kerf::v1::TradeoffReference& r : experiment.references()) {
    absl::StrAppendFormat(&out,
                          "\n%s: %s; reference (%s) (%.6g, %.6g, %.6g)\n\n"
                          "| n | tets | law | integration | step (ms) | wall s per simulated s | "
                          "value | error | Pareto | default |\n"
                          "|---|---|---|---|---|---|---|---|---|---|\n",
                          r.load(), r.quantity(), r.solver(), r.value(0), r.value(1), r.value(2));
    for (const kerf::v1::TradeoffRow& row : experiment.rows()) {
      if (row.load() != r.load()) continue;
      absl::StrAppendFormat(
          &out, "| %u | %u | %s | %s | %.3g | %.3g | (%.5g, %.5g, %.5g) | %s | %s | %s |\n",
          row.resolution(), row.tets(), row.law(), row.integration(), 1e3 * row.time_step(),
          row.wall_seconds_per_simulated_second(), row.value(0), row.value(1), row.value(2),
          row.blew_up() ? "blew up" : absl::StrFormat("%.3g", row.relative_error()),
          row.pareto() ? "yes" : "", row.default_configuration() ? "yes" : "");
    }
  }
  return out;
}

}  // namespace kerf::cli
