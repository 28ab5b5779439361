#include "cli/replay_command.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <memory>

#include "absl/strings/escaping.h"
#include "absl/strings/str_cat.h"
#include "absl/strings/str_format.h"
#include "absl/strings/str_split.h"
#include "absl/synchronization/notification.h"
#include "absl/time/clock.h"
#include "cli/command_args.h"
#include "cli/json_output.h"
#include "kerf/v1/replay_report.pb.h"
#include "mesh/io/mesh_file.h"
#include "mesh/io/vtu_writer.h"
#include "service/grpc_server.h"
#include "service/level_view.h"
#include "service/recorded_session.h"
#include "service/session_registry.h"
#include "service/simulator_service.h"

namespace kerf::cli {
namespace {

constexpr absl::string_view kReplayUsage =
    "kerf replay JOURNAL [--speed X] [--listen HOST:PORT] [--export-at T,T,...|end] "
    "[--out-prefix P] [--linger S] [--json]";

// One mesh to write: at the first tick whose simulation time reaches `time`, or at `tick`.
struct PendingExport {
  double time = 0;
  std::uint64_t tick = 0;  // nonzero: exactly this tick ("end")
  bool done = false;
};

absl::StatusOr<std::vector<PendingExport>> ParseExportTimes(absl::string_view list,
                                                            std::uint64_t last_tick,
                                                            double rate_hz) {
  std::vector<PendingExport> exports;
  for (const absl::string_view item : absl::StrSplit(list, ',', absl::SkipEmpty())) {
    if (item == "end") {
      exports.push_back(
          {static_cast<double>(last_tick) / rate_hz, std::max<std::uint64_t>(last_tick, 1)});
      continue;
    }
    absl::StatusOr<double> time = ParseDoubleArg(item, "--export-at");
    if (!time.ok()) return time.status();
    if (!(*time >= 0 && *time <= 24 * 3600)) {
      return absl::InvalidArgumentError(
          absl::StrCat("--export-at: ", item, " is not a time in seconds between 0 and a day"));
    }
    exports.push_back({*time, 0});
  }
  return exports;
}

// What the physics thread records as the replay goes (read after `finished`).
struct Progress {
  std::vector<PendingExport> pending;
  std::string prefix;
  std::uint64_t end_tick = 0;
  kerf::v1::ReplayReport* report = nullptr;
  absl::Status error;
  absl::Notification finished;
};

void AfterTick(Progress& p, std::uint64_t tick, double time, const sim::Simulation& simulation) {
  if (p.finished.HasBeenNotified()) return;
  for (PendingExport& e : p.pending) {
    if (e.done || (e.tick != 0 ? tick < e.tick : time < e.time)) continue;
    e.done = true;
    kerf::v1::ReplayReport::Export& out = *p.report->add_exports();
    out.set_requested_time(e.time);
    out.set_simulation_time(time);
    out.set_tick(tick);
    out.set_path(absl::StrFormat("%s-t%.3f.vtu", p.prefix, e.time));
    out.set_model_sha256(absl::BytesToHexString(service::ModelSha256(simulation)));
    const absl::Status written = mesh::WriteTextFile(
        out.path(),
        mesh::FormatVtu(simulation.mesh(), {{mesh::RestPositionArray(simulation.mesh())}, {}}));
    if (!written.ok() && p.error.ok()) p.error = written;
  }
  const bool exported = std::all_of(p.pending.begin(), p.pending.end(),
                                    [](const PendingExport& e) { return e.done; });
  if (exported && tick >= p.end_tick) {
    p.report->set_ticks(tick);
    p.report->set_simulated_seconds(time);
    p.report->set_tets_after(simulation.mesh().tet_count());
    p.finished.Notify();
  }
}

}  // namespace

absl::StatusOr<std::string> RunReplayCommand(const std::vector<absl::string_view>& args) {
  CommandArgs rest(args);
  const bool json = rest.TakeFlag("--json");
  std::optional<std::vector<absl::string_view>> speed_arg, listen_arg, export_arg, prefix_arg,
      linger_arg;
  for (auto [name, arg] : {std::pair{"--speed", &speed_arg},
                           {"--listen", &listen_arg},
                           {"--export-at", &export_arg},
                           {"--out-prefix", &prefix_arg},
                           {"--linger", &linger_arg}}) {
    absl::StatusOr<std::optional<std::vector<absl::string_view>>> taken = rest.TakeOption(name, 1);
    if (!taken.ok()) return taken.status();
    *arg = *std::move(taken);
  }
  absl::StatusOr<std::vector<absl::string_view>> journal_arg =
      rest.TakePositionals(1, kReplayUsage);
  if (!journal_arg.ok()) return journal_arg.status();
  const std::string journal((*journal_arg)[0]);

  double speed = 1, linger = 0;
  if (speed_arg) {
    absl::StatusOr<double> v = ParseDoubleArg((*speed_arg)[0], "--speed");
    if (!v.ok()) return v.status();
    if (!(*v > 0 && *v <= 1000)) {
      return absl::InvalidArgumentError(
          absl::StrCat("--speed must be in (0, 1000] simulated seconds per second, got ", *v));
    }
    speed = *v;
  }
  if (linger_arg) {
    absl::StatusOr<double> v = ParseDoubleArg((*linger_arg)[0], "--linger");
    if (!v.ok()) return v.status();
    if (!(*v >= 0 && *v <= 3600)) {
      return absl::InvalidArgumentError(absl::StrCat("--linger must be in [0, 3600] s, got ", *v));
    }
    linger = *v;
  }
  const std::string listen = listen_arg ? std::string((*listen_arg)[0]) : "127.0.0.1:0";

  absl::StatusOr<service::RecordedSession> recorded = service::ReadRecordedSession(journal);
  if (!recorded.ok()) return recorded.status();
  if (!recorded->warning.empty())
    std::fprintf(stderr, "kerf: warning: %s\n", recorded->warning.c_str());

  kerf::v1::ReplayReport report;
  report.set_journal(journal);
  report.set_recorded_session_id(recorded->start.session_id());
  report.set_speed(speed);
  report.set_warning(recorded->warning);
  for (const kerf::v1::JournalRecord& r : recorded->events) {
    if (r.has_pose()) report.set_poses(report.poses() + 1);
    if (r.has_withdrawal()) report.set_withdrawals(report.withdrawals() + 1);
  }

  Progress progress;
  progress.report = &report;
  progress.end_tick = std::max<std::uint64_t>(recorded->last_tick, 1);
  progress.prefix =
      prefix_arg
          ? std::string((*prefix_arg)[0])
          : journal.substr(0, journal.size() - (absl::EndsWith(journal, ".journal") ? 8 : 0));
  if (export_arg) {
    absl::StatusOr<std::vector<PendingExport>> exports =
        ParseExportTimes((*export_arg)[0], recorded->last_tick, recorded->start.physics_rate_hz());
    if (!exports.ok()) return exports.status();
    progress.pending = *std::move(exports);
  }

  service::RegistryOptions options;
  options.max_sessions = 1;
  service::SessionOptions session_options;
  session_options.speed = speed;
  session_options.after_tick = [&progress](std::uint64_t tick, double time,
                                           const sim::Simulation& simulation) {
    AfterTick(progress, tick, time, simulation);
  };
  service::SessionRegistry registry(options);
  const absl::Time start = absl::Now();
  absl::StatusOr<service::CreatedSession> created =
      registry.CreateReplay(*recorded, session_options);
  if (!created.ok()) return created.status();
  report.set_replay_session_id(created->session->id());
  report.set_tets_before(created->session->Info().tets());  // a tick or so in: no cut yet

  service::SimulatorService simulator(&registry);
  std::unique_ptr<grpc::Server> server;
  if (!listen.empty()) {
    service::ServerConfig config;
    config.listen = listen;
    absl::StatusOr<service::RunningServer> running = service::StartServer(config, &simulator);
    if (!running.ok()) {
      registry.CloseAll(absl::CancelledError("the replay could not be served"));
      return running.status();
    }
    server = std::move(running->server);
    report.set_listening(absl::StrCat(listen.substr(0, listen.rfind(':')), ":", running->port));
    std::printf("kerf replay: session %s on %s, observer token %s\n",
                created->session->id().c_str(), report.listening().c_str(),
                created->tokens.observer.c_str());
    std::fflush(stdout);
  }
  progress.finished.WaitForNotification();
  report.set_wall_seconds(absl::ToDoubleSeconds(absl::Now() - start));
  absl::SleepFor(absl::Seconds(linger));
  registry.CloseAll(absl::CancelledError("the replay is over"));
  if (server != nullptr) server->Shutdown(std::chrono::system_clock::now());
  if (!progress.error.ok()) return progress.error;

  if (json) return FormatProtoJson(report);
  std::string text = absl::StrFormat(
      "replayed %s: %d poses and %d withdrawals over %.3f s of simulation in %.3f s (speed "
      "%g); %d tets before, %d after\n",
      journal, report.poses(), report.withdrawals(), report.simulated_seconds(),
      report.wall_seconds(), speed, report.tets_before(), report.tets_after());
  for (const auto& e : report.exports()) {
    absl::StrAppendFormat(&text, "wrote %s (t = %.6f s, tick %d, model sha256 %s)\n", e.path(),
                          e.simulation_time(), e.tick(), e.model_sha256());
  }
  return text;
}

}  // namespace kerf::cli
