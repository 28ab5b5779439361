// A session: one tissue model stepped in real time on its own thread, one cutter feeding it
// blade poses, and subscribers receiving frames at their level.
//
// The physics thread ticks at a fixed rate (default 1 kHz); a tick applies the poses that are
// due (interpolating between poses that come slower than the ticks), advances the model by the
// tick's period in steps of the scene's time step, and makes frames at the observers' rate
// (default 60 Hz, spread evenly over the ticks) and after every tick (or at its own rate) for
// the cutter. Each frame is
// made and serialized once per view and offered to every subscriber's FrameQueue, which never
// blocks the tick.
//
// Determinism: the model's state after tick n depends only on the scene and on the events
// (poses applied, blade withdrawn) of ticks 1..n. A session with a journal appends each tick's
// events to it at the end of the tick; a session given recorded events applies them at their
// ticks, which rebuilds the recorded model bit for bit (a restore, or a replay to watch).
#pragma once

#include <cmath>
#include <cstdint>
#include <deque>
#include <functional>
#include <memory>
#include <optional>
#include <string>
#include <thread>
#include <vector>

#include "absl/status/statusor.h"
#include "absl/synchronization/mutex.h"
#include "absl/time/time.h"
#include "cut/blade.h"
#include "kerf/v1/frame.pb.h"
#include "kerf/v1/journal.pb.h"
#include "kerf/v1/simulator.pb.h"
#include "service/frame_queue.h"
#include "service/journal_file.h"
#include "service/level_view.h"
#include "service/session_tokens.h"
#include "sim/scene.h"
#include "sim/simulation.h"

namespace kerf::service {

struct SessionOptions {
  double physics_rate_hz = 1000;
  double frame_rate_hz = 60;           // for observers
  std::size_t max_subscribers = 64;    // observers, per session
  std::size_t max_waiting_frames = 8;  // per subscriber before a resync
  double max_pose_lead_seconds = 2;    // how far ahead of the session a pose may be queued
  std::size_t max_queued_poses = 4096;
  cut::BladeLimits blade_limits;
  double speed = 1;  // simulated seconds per wall-clock second (a replay may go faster or slower)
  // Called on the physics thread after every tick, with the model (for exports).
  std::function<void(std::uint64_t tick, double simulation_time, const sim::Simulation&)>
      after_tick;
};

// What a session is made from.
struct SessionSetup {
  std::string id;
  sim::Scene scene;
  SessionTokens tokens;
  // Where the session appends its events (its start record already written); none: no journal.
  std::unique_ptr<JournalWriter> journal;
  // Recorded events (JournalPose and JournalWithdrawal records, ticks not decreasing), applied
  // at their ticks; the session refuses cutters until the last one is applied.
  std::vector<kerf::v1::JournalRecord> recorded;
  // Ticks 1..this run at once in Create, before real time starts (a restore catching up).
  std::uint64_t catch_up_to_tick = 0;
};

// A subscriber's handle: its queue, and what it asked for. Made by Session::Subscribe.
struct Subscription {
  kerf::v1::Level level;
  bool cutter = false;
  std::unique_ptr<FrameQueue> queue;
  // Called once if the session ends the subscription (it was closed or is shutting down).
  std::function<void(const absl::Status&)> on_end;
};

class Session {
 public:
  // INVALID_ARGUMENT for a scene the simulation cannot take or bad rates. Catches up, then
  // starts the thread.
  static absl::StatusOr<std::unique_ptr<Session>> Create(SessionSetup setup,
                                                         const SessionOptions& options);
  ~Session();  // Close(CANCELLED "session closed")

  // Stops the thread and ends every subscription with `why`. With `for_good`, the journal
  // records the end (the session is not restored). Idempotent.
  void Close(const absl::Status& why, bool for_good = false);

  const std::string& id() const { return id_; }
  const SessionTokens& tokens() const { return tokens_; }

  // Adds an observer at `level`; `start_write` writes one frame (see FrameQueue).
  // FAILED_PRECONDITION for a level the scene does not offer, RESOURCE_EXHAUSTED at the
  // subscriber limit, INVALID_ARGUMENT for an unspecified level.
  absl::StatusOr<std::shared_ptr<Subscription>> Observe(
      kerf::v1::Level level, std::function<void(const SerializedFrame&)> start_write,
      std::function<void(const absl::Status&)> on_end);
  // Takes the blade: FAILED_PRECONDITION while another cutter holds it or recorded events are
  // still being replayed. Frames at `level`
  // every `frame_rate_hz` (0: every tick).
  absl::StatusOr<std::shared_ptr<Subscription>> BeginCut(
      kerf::v1::Level level, double frame_rate_hz,
      std::function<void(const SerializedFrame&)> start_write,
      std::function<void(const absl::Status&)> on_end);
  // Queues a pose of the current cut: INVALID_ARGUMENT (and nothing queued) for a bad one,
  // RESOURCE_EXHAUSTED for one too far ahead of the session or beyond the queue's bound (send
  // poses in real time).
  absl::Status SubmitPose(const kerf::v1::BladePose& pose);
  // The cutter has sent its last pose: the poses it sent are still applied, then the blade is
  // withdrawn, the frame of that tick is offered, and `on_withdrawn` is called (on the
  // physics thread).
  void EndCut(std::function<void()> on_withdrawn = nullptr);
  void Unsubscribe(const std::shared_ptr<Subscription>& subscription);

  // Calls `done` with a keyframe made afresh from the model at the observer frame `sequence`
  // of `level` (0: the next one), with that frame's sequence number: on the physics thread when
  // the frame is due, or at once with INVALID_ARGUMENT / FAILED_PRECONDITION for a level not
  // offered, OUT_OF_RANGE for a frame already made or more than a minute ahead,
  // RESOURCE_EXHAUSTED with too many waiting, CANCELLED when the session closes first.
  void Snapshot(kerf::v1::Level level, std::uint64_t sequence,
                std::function<void(absl::StatusOr<kerf::v1::Frame>)> done);

  kerf::v1::SessionInfo Info() const;

 private:
  struct View {
    LevelView frames;
    double frames_per_tick;  // at most 1
    // The frames due by tick `tick` (from 1): spread evenly over the ticks.
    std::uint64_t FramesBy(std::uint64_t tick) const {
      return static_cast<std::uint64_t>(std::floor(static_cast<double>(tick) * frames_per_tick));
    }
    bool DueAt(std::uint64_t tick) const { return FramesBy(tick) != FramesBy(tick - 1); }
    std::vector<std::shared_ptr<Subscription>> subscribers;
  };
  struct SnapshotRequest {
    kerf::v1::Level level;
    std::uint64_t sequence;  // 0: the next frame
    std::function<void(absl::StatusOr<kerf::v1::Frame>)> done;
  };

  Session(std::string id, SessionTokens tokens, const SessionOptions& options)
      : id_(std::move(id)), options_(options), tokens_(std::move(tokens)) {}
  void Run();
  void Tick() ABSL_EXCLUSIVE_LOCKS_REQUIRED(mutex_);
  void ApplyRecordedEvents(std::uint64_t tick) ABSL_EXCLUSIVE_LOCKS_REQUIRED(mutex_);
  void ApplyDuePoses(std::uint64_t tick, double until) ABSL_EXCLUSIVE_LOCKS_REQUIRED(mutex_);
  // The simulation's refusal, if it refuses (then nothing changed).
  absl::Status ApplyPose(const cut::BladePose& pose, double blade_time)
      ABSL_EXCLUSIVE_LOCKS_REQUIRED(mutex_);
  absl::Status Withdraw() ABSL_EXCLUSIVE_LOCKS_REQUIRED(mutex_);
  // Withdraws the blade at `tick` and journals it; a failure ends the cut (EndCutWith).
  void WithdrawBlade(std::uint64_t tick) ABSL_EXCLUSIVE_LOCKS_REQUIRED(mutex_);
  // Ends the cut with `why` (logged, and the cutter's stream ended with it): its queued poses
  // are dropped and the blade withdrawn at the next tick. What it cut stays cut.
  void EndCutWith(const absl::Status& why) ABSL_EXCLUSIVE_LOCKS_REQUIRED(mutex_);
  void ReportReplayFailure(std::uint64_t tick, const absl::Status& status) const;
  void WriteJournal() ABSL_EXCLUSIVE_LOCKS_REQUIRED(mutex_);
  // Trims the mesh's change log to what its readers have not read yet (the simulation's, and
  // the views someone watches), so that it follows the cut, not the clock.
  void DiscardReadChanges() ABSL_EXCLUSIVE_LOCKS_REQUIRED(mutex_);
  void Publish(View& view, std::uint64_t sequence, const TickReport& report)
      ABSL_EXCLUSIVE_LOCKS_REQUIRED(mutex_);
  // Answers the snapshot requests of `view`'s level due at this tick's frame `sequence`.
  void TakeSnapshots(const View& view, std::uint64_t sequence, const TickReport& report)
      ABSL_EXCLUSIVE_LOCKS_REQUIRED(mutex_);
  // INVALID_ARGUMENT for no or an unknown level, FAILED_PRECONDITION for one the scene does not
  // offer.
  absl::Status CheckOffered(kerf::v1::Level level) const;
  absl::Status Closed() const;  // CANCELLED "session ID closed"
  void StopThread();

  const std::string id_;
  const SessionOptions options_;
  const SessionTokens tokens_;
  std::string scene_name_;
  std::vector<kerf::v1::Level> levels_;
  std::uint32_t original_vertex_bound_ = 0;
  double tick_seconds_ = 0;

  mutable absl::Mutex mutex_;
  std::unique_ptr<sim::Simulation> simulation_ ABSL_GUARDED_BY(mutex_);
  double simulation_time_ ABSL_GUARDED_BY(mutex_) = 0;
  std::uint64_t ticks_ ABSL_GUARDED_BY(mutex_) = 0;
  std::uint64_t overruns_ ABSL_GUARDED_BY(mutex_) = 0;
  std::uint64_t poses_applied_ ABSL_GUARDED_BY(mutex_) = 0;
  std::uint64_t poses_received_ ABSL_GUARDED_BY(mutex_) = 0;
  std::uint64_t frames_sent_to_departed_ ABSL_GUARDED_BY(mutex_) = 0;  // observers gone
  // Info's count of boundary triangles, and the topology it was counted on.
  mutable std::optional<std::size_t> surface_triangles_ ABSL_GUARDED_BY(mutex_);
  mutable mesh::ChangeMark surface_counted_at_ ABSL_GUARDED_BY(mutex_);
  double last_tick_seconds_ ABSL_GUARDED_BY(mutex_) = 0;
  std::vector<std::unique_ptr<View>> observer_views_ ABSL_GUARDED_BY(mutex_);  // by level
  std::unique_ptr<View> cutter_view_ ABSL_GUARDED_BY(mutex_);
  // The blade: poses on the simulation's clock, waiting to be applied.
  std::deque<cut::BladePose> poses_ ABSL_GUARDED_BY(mutex_);
  std::optional<cut::BladePose> last_submitted_ ABSL_GUARDED_BY(mutex_);
  std::optional<cut::BladePose> last_applied_ ABSL_GUARDED_BY(mutex_);
  std::optional<cut::BladePose> before_last_applied_ ABSL_GUARDED_BY(mutex_);
  double pose_time_offset_ ABSL_GUARDED_BY(mutex_) = 0;  // simulation time - client time
  double blade_time_ ABSL_GUARDED_BY(mutex_) = 0;        // client time of the last pose applied
  bool withdraw_when_done_ ABSL_GUARDED_BY(mutex_) = false;
  std::function<void()> on_withdrawn_ ABSL_GUARDED_BY(mutex_);
  bool withdrawn_this_tick_ ABSL_GUARDED_BY(mutex_) = false;
  std::vector<SnapshotRequest> snapshots_ ABSL_GUARDED_BY(mutex_);
  // The journal, and the records of this tick not yet written to it.
  std::unique_ptr<JournalWriter> journal_ ABSL_GUARDED_BY(mutex_);
  std::vector<kerf::v1::JournalRecord> unwritten_ ABSL_GUARDED_BY(mutex_);
  std::deque<kerf::v1::JournalRecord> recorded_ ABSL_GUARDED_BY(mutex_);  // still to apply
  bool stopping_ ABSL_GUARDED_BY(mutex_) = false;
  std::thread thread_;
};

}  // namespace kerf::service
