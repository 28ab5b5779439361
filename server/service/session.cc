#include "service/session.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <utility>

#include "absl/strings/str_cat.h"
#include "base/check.h"
#include "mesh/boundary_surface.h"
#include "sim/blade_messages.h"
#include "sim/tool_reaction.h"

namespace kerf::service {
namespace {

// At most this many steps of the scene's time step per tick; past it the model runs slower
// than real time (counted as an overrun) rather than stalling the session.
constexpr int kMaxStepsPerTick = 200;

constexpr std::size_t kMaxWaitingSnapshots = 64;

bool ChangesTopology(const kerf::v1::Frame& f) {
  return f.removed_vertices_size() + f.added_vertices_size() + f.removed_elements_size() +
             f.added_elements_size() >
         0;
}

SerializedFrame Serialize(const kerf::v1::Frame& frame) {
  return {std::make_shared<const std::string>(frame.SerializeAsString()), frame.sequence(),
          ChangesTopology(frame), frame.keyframe()};
}

}  // namespace

absl::StatusOr<std::unique_ptr<Session>> Session::Create(SessionSetup setup,
                                                         const SessionOptions& options) {
  if (!(options.physics_rate_hz > 0 && options.physics_rate_hz <= 100000)) {
    return absl::InvalidArgumentError(
        absl::StrCat("physics_rate_hz must be in (0, 100000], got ", options.physics_rate_hz));
  }
  if (!(options.frame_rate_hz > 0 && options.frame_rate_hz <= options.physics_rate_hz)) {
    return absl::InvalidArgumentError(
        absl::StrCat("frame_rate_hz must be positive and at most the physics rate (",
                     options.physics_rate_hz, " Hz), got ", options.frame_rate_hz));
  }
  if (!(options.speed > 0 && options.speed <= 1000)) {
    return absl::InvalidArgumentError(
        absl::StrCat("speed must be in (0, 1000], got ", options.speed));
  }
  std::unique_ptr<Session> session(
      new Session(std::move(setup.id), std::move(setup.tokens), options));
  session->scene_name_ = setup.scene.name;
  for (const int level : setup.scene.needs.levels()) {
    session->levels_.push_back(static_cast<kerf::v1::Level>(level));
  }
  if (session->levels_.empty()) {
    session->levels_ = {kerf::v1::SURFACE, kerf::v1::VOLUME, kerf::v1::FORCES};
  }
  setup.scene.blade_limits = options.blade_limits;  // the cutter refuses what SubmitPose does
  absl::StatusOr<std::unique_ptr<sim::Simulation>> simulation =
      sim::Simulation::Create(std::move(setup.scene));
  if (!simulation.ok()) return simulation.status();
  session->tick_seconds_ = 1.0 / options.physics_rate_hz;
  const double frames_per_tick = options.frame_rate_hz / options.physics_rate_hz;
  {
    absl::MutexLock lock(&session->mutex_);
    session->simulation_ = *std::move(simulation);
    session->original_vertex_bound_ = session->simulation_->mesh().vertex_index_bound();
    for (int level = 0; level <= kerf::v1::FORCES; ++level) {
      session->observer_views_.push_back(std::make_unique<View>(
          View{LevelView(static_cast<kerf::v1::Level>(level), *session->simulation_),
               frames_per_tick,
               {}}));
    }
    session->journal_ = std::move(setup.journal);
    session->recorded_.assign(std::make_move_iterator(setup.recorded.begin()),
                              std::make_move_iterator(setup.recorded.end()));
    while (session->ticks_ < setup.catch_up_to_tick) session->Tick();
  }
  session->thread_ = std::thread([s = session.get()] { s->Run(); });
  return session;
}

Session::~Session() { Close(Closed()); }

void Session::StopThread() {
  {
    absl::MutexLock lock(&mutex_);
    stopping_ = true;
  }
  if (thread_.joinable()) thread_.join();
}

void Session::Close(const absl::Status& why, bool for_good) {
  StopThread();
  std::vector<std::shared_ptr<Subscription>> ending;
  std::vector<SnapshotRequest> snapshots;
  {
    absl::MutexLock lock(&mutex_);
    if (for_good && journal_ != nullptr) {
      kerf::v1::JournalRecord end;
      end.mutable_end()->set_tick(std::max<std::uint64_t>(ticks_, 1));
      unwritten_.push_back(std::move(end));
      WriteJournal();
    }
    journal_.reset();
    for (auto& view : observer_views_) {
      ending.insert(ending.end(), view->subscribers.begin(), view->subscribers.end());
      view->subscribers.clear();
    }
    if (cutter_view_ != nullptr) {
      ending.insert(ending.end(), cutter_view_->subscribers.begin(),
                    cutter_view_->subscribers.end());
      cutter_view_.reset();
    }
    snapshots.swap(snapshots_);
  }
  for (SnapshotRequest& request : snapshots) {
    request.done(Closed());
  }
  std::uint64_t sent = 0;
  for (const auto& subscription : ending) {
    subscription->queue->Close();  // sent() is final from here
    if (!subscription->cutter) sent += subscription->queue->sent();
    if (subscription->on_end) subscription->on_end(why);
  }
  absl::MutexLock lock(&mutex_);
  frames_sent_to_departed_ += sent;
}

absl::Status Session::CheckOffered(kerf::v1::Level level) const {
  if (level == kerf::v1::LEVEL_UNSPECIFIED || !kerf::v1::Level_IsValid(level)) {
    return absl::InvalidArgumentError("level must be SURFACE, VOLUME or FORCES");
  }
  if (std::find(levels_.begin(), levels_.end(), level) == levels_.end()) {
    return absl::FailedPreconditionError(
        absl::StrCat("scene ", scene_name_, " does not offer ", kerf::v1::Level_Name(level)));
  }
  return absl::OkStatus();
}

absl::Status Session::Closed() const {
  return absl::CancelledError(absl::StrCat("session ", id_, " closed"));
}

absl::StatusOr<std::shared_ptr<Subscription>> Session::Observe(
    kerf::v1::Level level, std::function<void(const SerializedFrame&)> start_write,
    std::function<void(const absl::Status&)> on_end) {
  if (absl::Status s = CheckOffered(level); !s.ok()) return s;
  absl::MutexLock lock(&mutex_);
  if (stopping_) return Closed();
  std::size_t observers = 0;
  for (const auto& view : observer_views_) observers += view->subscribers.size();
  if (observers >= options_.max_subscribers) {
    return absl::ResourceExhaustedError(absl::StrCat("session ", id_, " has its limit of ",
                                                     options_.max_subscribers, " observers"));
  }
  auto subscription = std::make_shared<Subscription>(Subscription{
      level, false, std::make_unique<FrameQueue>(options_.max_waiting_frames, start_write),
      std::move(on_end)});
  observer_views_[level]->subscribers.push_back(subscription);
  return subscription;
}

absl::StatusOr<std::shared_ptr<Subscription>> Session::BeginCut(
    kerf::v1::Level level, double frame_rate_hz,
    std::function<void(const SerializedFrame&)> start_write,
    std::function<void(const absl::Status&)> on_end) {
  if (level == kerf::v1::LEVEL_UNSPECIFIED) level = kerf::v1::FORCES;
  if (absl::Status s = CheckOffered(level); !s.ok()) return s;
  if (!(frame_rate_hz >= 0 && frame_rate_hz <= options_.physics_rate_hz)) {
    return absl::InvalidArgumentError(
        absl::StrCat("frame_rate_hz must be between 0 (every tick) and the physics rate (",
                     options_.physics_rate_hz, " Hz), got ", frame_rate_hz));
  }
  absl::MutexLock lock(&mutex_);
  if (stopping_) return Closed();
  if (cutter_view_ != nullptr) {
    return absl::FailedPreconditionError(
        absl::StrCat("session ", id_, " already has a cutter; one at a time"));
  }
  if (!recorded_.empty()) {
    return absl::FailedPreconditionError(
        absl::StrCat("session ", id_, " is replaying a recorded cut; watch it with Observe"));
  }
  const double frames_per_tick =
      frame_rate_hz == 0 ? 1.0 : frame_rate_hz / options_.physics_rate_hz;
  cutter_view_ = std::make_unique<View>(View{LevelView(level, *simulation_), frames_per_tick, {}});
  auto subscription = std::make_shared<Subscription>(Subscription{
      level, true, std::make_unique<FrameQueue>(options_.max_waiting_frames, start_write),
      std::move(on_end)});
  cutter_view_->subscribers.push_back(subscription);
  last_submitted_.reset();
  // The blade of a cutter that left without a word comes out before this cut's first pose
  // (this cut's frames start from a keyframe; nobody waits for that withdrawal's frame).
  if (withdraw_when_done_) {
    WithdrawBlade(ticks_ + 1);
    withdrawn_this_tick_ = false;
  }
  on_withdrawn_ = nullptr;
  return subscription;
}

absl::Status Session::SubmitPose(const kerf::v1::BladePose& message) {
  absl::StatusOr<cut::BladePose> pose = sim::BladePoseFromProto(message);
  if (!pose.ok()) return pose.status();
  absl::MutexLock lock(&mutex_);
  if (cutter_view_ == nullptr) {
    return absl::FailedPreconditionError("no cut in progress: send CutStart first");
  }
  if (!std::isfinite(pose->time)) {
    return absl::InvalidArgumentError(absl::StrCat("pose time must be finite, got ", pose->time));
  }
  // The first pose of a cut is due at the next tick; the others keep their spacing.
  const double offset = last_submitted_ ? pose_time_offset_ : simulation_time_ - pose->time;
  cut::BladePose due = *pose;
  due.time += offset;
  if (absl::Status s = cut::ValidatePose(due, last_submitted_ ? &*last_submitted_ : nullptr,
                                         options_.blade_limits);
      !s.ok()) {
    return s;
  }
  if (due.time > simulation_time_ + options_.max_pose_lead_seconds ||
      poses_.size() >= options_.max_queued_poses) {
    return absl::ResourceExhaustedError(absl::StrCat(
        "pose at ", pose->time, " s is ", due.time - simulation_time_,
        " s ahead of the session, with ", poses_.size(),
        " poses waiting; send poses in real time (at most ", options_.max_pose_lead_seconds,
        " s and ", options_.max_queued_poses, " poses ahead)"));
  }
  pose_time_offset_ = offset;
  last_submitted_ = due;
  poses_.push_back(due);
  ++poses_received_;
  return absl::OkStatus();
}

void Session::EndCut(std::function<void()> on_withdrawn) {
  absl::MutexLock lock(&mutex_);
  withdraw_when_done_ = true;
  on_withdrawn_ = std::move(on_withdrawn);
}

void Session::Unsubscribe(const std::shared_ptr<Subscription>& subscription) {
  subscription->queue->Close();
  absl::MutexLock lock(&mutex_);
  if (subscription->cutter) {
    if (cutter_view_ != nullptr && !cutter_view_->subscribers.empty() &&
        cutter_view_->subscribers.front() == subscription) {
      // Gone without a word: the blade stops where the session has it and comes out.
      cutter_view_.reset();
      poses_.clear();
      withdraw_when_done_ = true;
      on_withdrawn_ = nullptr;
    }
    return;
  }
  auto& list = observer_views_[subscription->level]->subscribers;
  const auto gone = std::remove(list.begin(), list.end(), subscription);
  if (gone != list.end()) frames_sent_to_departed_ += subscription->queue->sent();
  list.erase(gone, list.end());
}

void Session::Snapshot(kerf::v1::Level level, std::uint64_t sequence,
                       std::function<void(absl::StatusOr<kerf::v1::Frame>)> done) {
  if (absl::Status s = CheckOffered(level); !s.ok()) return done(s);
  absl::MutexLock lock(&mutex_);
  if (stopping_) return done(Closed());
  const View& view = *observer_views_[level];
  const std::uint64_t made = view.FramesBy(ticks_);
  const std::uint64_t limit = made + static_cast<std::uint64_t>(60 * options_.frame_rate_hz);
  if (sequence != 0 && (sequence <= made || sequence > limit)) {
    return done(absl::OutOfRangeError(absl::StrCat(
        "frame ", sequence, " of ", kerf::v1::Level_Name(level), ": the session has made ", made,
        " frames; ask for one of the next minute (up to ", limit, ")")));
  }
  if (snapshots_.size() >= kMaxWaitingSnapshots) {
    return done(absl::ResourceExhaustedError(absl::StrCat(
        "session ", id_, " has ", kMaxWaitingSnapshots, " snapshot requests waiting")));
  }
  snapshots_.push_back({level, sequence, std::move(done)});
}

kerf::v1::SessionInfo Session::Info() const {
  kerf::v1::SessionInfo info;
  info.set_session_id(id_);
  info.set_scene_name(scene_name_);
  info.set_physics_rate_hz(options_.physics_rate_hz);
  info.set_frame_rate_hz(options_.frame_rate_hz);
  for (const kerf::v1::Level level : levels_) info.add_levels(level);
  absl::MutexLock lock(&mutex_);
  info.set_simulation_time(simulation_time_);
  info.set_tets(simulation_->mesh().tet_count());
  // Extracting the boundary is O(mesh) with the physics waiting on the lock: counted again only
  // after the topology changed.
  const mesh::ChangeMark mark = simulation_->mesh().change_log().Mark();
  if (!surface_triangles_ || mark != surface_counted_at_) {
    surface_triangles_ = mesh::ExtractBoundarySurface(simulation_->mesh()).size();
    surface_counted_at_ = mark;
  }
  info.set_surface_triangles(*surface_triangles_);
  info.set_vertices(simulation_->mesh().vertex_count());
  std::size_t observers = 0;
  std::uint64_t frames_sent = frames_sent_to_departed_;
  for (const auto& view : observer_views_) {
    observers += view->subscribers.size();
    for (const auto& s : view->subscribers) frames_sent += s->queue->sent();
  }
  info.set_observers(static_cast<std::uint32_t>(observers));
  info.set_poses_received(poses_received_);
  info.set_observer_frames_sent(frames_sent);
  info.set_cutting(cutter_view_ != nullptr);
  return info;
}

void Session::Run() {
  const absl::Duration period = absl::Seconds(tick_seconds_ / options_.speed);
  absl::Time next = absl::Now();
  absl::MutexLock lock(&mutex_);
  while (!stopping_) {
    const absl::Time start = absl::Now();
    Tick();
    last_tick_seconds_ = absl::ToDoubleSeconds(absl::Now() - start);
    next += period;
    const absl::Time now = absl::Now();
    if (now > next) {
      ++overruns_;
      next = now;  // real time: a late tick is not made up for
    }
    mutex_.AwaitWithDeadline(absl::Condition(&stopping_), next);
  }
}

absl::Status Session::ApplyPose(const cut::BladePose& pose, double blade_time) {
  blade_time_ = blade_time;
  if (absl::Status s = simulation_->ApplyBladePose(pose); !s.ok()) return s;  // nothing changed
  before_last_applied_ = last_applied_;
  last_applied_ = pose;
  ++poses_applied_;
  return absl::OkStatus();
}

absl::Status Session::Withdraw() {
  withdrawn_this_tick_ = true;
  last_applied_.reset();
  before_last_applied_.reset();
  return simulation_->WithdrawBlade();
}

void Session::WithdrawBlade(std::uint64_t tick) {
  withdraw_when_done_ = false;
  const absl::Status withdrawn = Withdraw();
  if (journal_ != nullptr) {
    kerf::v1::JournalRecord record;
    record.mutable_withdrawal()->set_tick(tick);
    unwritten_.push_back(std::move(record));
  }
  if (!withdrawn.ok()) {
    EndCutWith(absl::Status(
        withdrawn.code(), absl::StrCat("the blade could not be withdrawn: ", withdrawn.message())));
  }
}

void Session::EndCutWith(const absl::Status& why) {
  std::fprintf(stderr, "kerf-server: session %s: %s\n", id_.c_str(),
               std::string(why.message()).c_str());
  poses_.clear();
  on_withdrawn_ = nullptr;
  if (last_applied_) withdraw_when_done_ = true;  // (a failed withdrawal is not tried again)
  if (cutter_view_ == nullptr) return;
  for (const auto& subscriber : cutter_view_->subscribers) {
    subscriber->queue->Close();
    if (subscriber->on_end) subscriber->on_end(why);
  }
  cutter_view_.reset();
}

void Session::ApplyRecordedEvents(std::uint64_t tick) {
  while (!recorded_.empty()) {
    const kerf::v1::JournalRecord& record = recorded_.front();
    if (record.has_pose()) {
      if (record.pose().tick() > tick) return;
      const absl::StatusOr<cut::BladePose> pose = sim::BladePoseFromProto(record.pose().pose());
      KERF_CHECK(pose.ok());  // checked by RecordedSessionOf
      // Recorded once applied, it applies again (a replay is deterministic). Should it not
      // (a journal of a server whose cutter differs), the restore goes on without it and says
      // so.
      if (absl::Status s = ApplyPose(*pose, record.pose().blade_time()); !s.ok()) {
        ReportReplayFailure(record.pose().tick(), s);
      }
    } else {
      if (record.withdrawal().tick() > tick) return;
      if (absl::Status s = Withdraw(); !s.ok()) ReportReplayFailure(record.withdrawal().tick(), s);
    }
    recorded_.pop_front();
    // The recorded cutter is gone (its server stopped): a blade it left in comes out, as that
    // of a cutter gone without a word does, and the next cut starts afresh.
    if (recorded_.empty() && last_applied_) withdraw_when_done_ = true;
  }
}

void Session::ReportReplayFailure(std::uint64_t tick, const absl::Status& status) const {
  std::fprintf(
      stderr, "kerf-server: session %s: the event recorded at tick %llu failed again: %s\n",
      id_.c_str(), static_cast<unsigned long long>(tick), std::string(status.message()).c_str());
}

void Session::ApplyDuePoses(std::uint64_t tick, double until) {
  // A pose the cutter refuses ends the cut (EndCutWith empties the queue).
  const auto apply = [&](const cut::BladePose& pose, double blade_time) {
    if (absl::Status s = ApplyPose(pose, blade_time); !s.ok()) {
      EndCutWith(absl::Status(
          s.code(), absl::StrCat("the pose at ", blade_time, " s was not applied: ", s.message(),
                                 "; the cut is ended and the blade withdrawn")));
      return;
    }
    if (journal_ == nullptr) return;
    kerf::v1::JournalRecord record;
    record.mutable_pose()->set_tick(tick);
    *record.mutable_pose()->mutable_pose() = sim::BladePoseToProto(pose);
    record.mutable_pose()->set_blade_time(blade_time);
    unwritten_.push_back(std::move(record));
  };
  while (!poses_.empty() && poses_.front().time <= until) {
    const cut::BladePose pose = poses_.front();
    poses_.pop_front();
    apply(pose, pose.time - pose_time_offset_);
  }
  if (!poses_.empty() && last_applied_ && last_applied_->time < until) {
    apply(cut::InterpolatePose(*last_applied_, poses_.front(), until), blade_time_);  // slow poses
  }
  if (poses_.empty() && withdraw_when_done_) WithdrawBlade(tick);
}

void Session::WriteJournal() {
  if (unwritten_.empty() || journal_ == nullptr) return;
  if (absl::Status s = journal_->Append(unwritten_); !s.ok()) {
    // The session goes on (the trainee's cut is not interrupted), without durability.
    std::fprintf(stderr, "kerf-server: session %s: %s; the session goes on without a journal\n",
                 id_.c_str(), std::string(s.message()).c_str());
    journal_.reset();
  }
  unwritten_.clear();
}

void Session::Tick() {
  // Tick n ends at n periods of simulated time; steps of the scene's time step follow it.
  const std::uint64_t tick = ticks_ + 1;
  const double target = static_cast<double>(tick) * tick_seconds_;
  ApplyRecordedEvents(tick);
  ApplyDuePoses(tick, target);
  if (simulation_->scene().method == kerf::v1::Integration::STATIC) {
    simulation_time_ = target;
  } else {
    int steps = 0;
    const double dt = simulation_->time_step();
    while (simulation_time_ + 0.5 * dt < target && steps < kMaxStepsPerTick) {
      simulation_->Step();
      simulation_time_ += dt;
      ++steps;
    }
    if (steps == kMaxStepsPerTick) {
      ++overruns_;
      simulation_time_ = target;  // slower than real time rather than stalled
    }
  }
  ++ticks_;
  WriteJournal();

  TickReport report;
  report.simulation_time = simulation_time_;
  report.blade_time = blade_time_;
  report.blade = last_applied_;
  kerf::v1::StepStatistics& s = report.statistics;
  s.set_physics_steps(ticks_);
  s.set_physics_step_seconds(last_tick_seconds_);
  s.set_overruns(overruns_);
  s.set_tets(simulation_->mesh().tet_count());
  s.set_vertices(simulation_->mesh().vertex_count());
  s.set_cut_tets(simulation_->cutter() ? simulation_->cutter()->statistics().cut_tets : 0);
  s.set_poses_applied(poses_applied_);

  // The views that make a frame this tick, with its sequence number; the nodal forces are
  // computed once for them all. Observer frames are numbered by tick, so that a replayed
  // session numbers them alike; a view nobody watches makes only the snapshots asked of it.
  struct Due {
    View* view;
    std::uint64_t sequence;
    bool snapshot;
  };
  std::vector<Due> due;
  for (auto& view : observer_views_) {
    if (!view->DueAt(ticks_)) continue;
    const std::uint64_t sequence = view->FramesBy(ticks_);
    const bool snapshot =
        std::any_of(snapshots_.begin(), snapshots_.end(), [&](const SnapshotRequest& r) {
          return r.level == view->frames.level() && (r.sequence == 0 || r.sequence == sequence);
        });
    if (view->subscribers.empty() && !snapshot) continue;
    due.push_back({view.get(), sequence, snapshot});
  }
  if (cutter_view_ != nullptr && (cutter_view_->DueAt(ticks_) || withdrawn_this_tick_)) {
    due.push_back({cutter_view_.get(), cutter_view_->frames.sequence() + 1, false});
  }
  // The elastic forces, computed once for the tool reaction and the frames that carry them.
  std::vector<Eigen::Vector3d> nodal_forces;
  const bool frames_need_forces = std::any_of(due.begin(), due.end(), [](const Due& d) {
    return d.view->frames.level() == kerf::v1::FORCES;
  });
  if (last_applied_ || frames_need_forces) nodal_forces = ComputeElasticForces(*simulation_);
  if (frames_need_forces) report.nodal_forces = nodal_forces;
  if (last_applied_) {
    const sim::ToolReaction reaction =
        sim::MeasureToolReaction(*simulation_, nodal_forces, *last_applied_, before_last_applied_);
    report.tool_force = reaction.force;
    report.tool_torque = reaction.torque;
  }
  for (const Due& d : due) {
    if (!d.view->subscribers.empty()) Publish(*d.view, d.sequence, report);
    if (d.snapshot) TakeSnapshots(*d.view, d.sequence, report);
  }
  if (withdrawn_this_tick_) {
    withdrawn_this_tick_ = false;
    if (on_withdrawn_) {  // the cut is over: the blade is free for the next cutter at once
      if (cutter_view_ != nullptr) {
        for (const auto& subscriber : cutter_view_->subscribers) subscriber->queue->Close();
        cutter_view_.reset();
      }
      std::exchange(on_withdrawn_, nullptr)();
    }
  }
  DiscardReadChanges();
  if (options_.after_tick) options_.after_tick(ticks_, simulation_time_, *simulation_);
}

void Session::DiscardReadChanges() {
  // The views someone watches read on from their last frame; the others compare with the mesh
  // when they are watched again.
  mesh::ChangeMark keep = simulation_->mesh().change_log().Mark();
  const auto older = [&](const View& view) {
    if (!view.subscribers.empty() && view.frames.synced().sequence < keep.sequence) {
      keep = view.frames.synced();
    }
  };
  for (const auto& view : observer_views_) older(*view);
  if (cutter_view_ != nullptr) older(*cutter_view_);
  simulation_->DiscardChangesBefore(keep);
}

void Session::Publish(View& view, std::uint64_t sequence, const TickReport& report) {
  const kerf::v1::Frame frame = view.frames.Advance(report, sequence);
  const SerializedFrame delta = Serialize(frame);
  std::optional<SerializedFrame> keyframe;  // made once, for those who need one
  for (const auto& subscriber : view.subscribers) {
    if (subscriber->queue->NeedsKeyframe()) {
      if (!keyframe) keyframe = Serialize(view.frames.Keyframe());
      subscriber->queue->OfferKeyframe(*keyframe);
    } else {
      subscriber->queue->Offer(delta);
    }
  }
}

void Session::TakeSnapshots(const View& view, std::uint64_t sequence, const TickReport& report) {
  std::vector<SnapshotRequest> answered;
  for (auto it = snapshots_.begin(); it != snapshots_.end();) {
    if (it->level == view.frames.level() && (it->sequence == 0 || it->sequence == sequence)) {
      answered.push_back(std::move(*it));
      it = snapshots_.erase(it);
    } else {
      ++it;
    }
  }
  if (answered.empty()) return;
  const kerf::v1::Frame snapshot =
      MakeSnapshot(view.frames.level(), *simulation_, original_vertex_bound_, sequence, report);
  for (SnapshotRequest& request : answered) request.done(snapshot);
}

}  // namespace kerf::service
