#include "service/session.h"

#include <algorithm>
#include <cmath>
#include <utility>

#include "absl/strings/str_cat.h"
#include "sim/tool_reaction.h"

namespace kerf::service {
namespace {

// At most this many steps of the scene's time step per tick; past it the model runs slower
// than real time (counted as an overrun) rather than stalling the session.
constexpr int kMaxStepsPerTick = 200;

cut::BladePose Interpolate(const cut::BladePose& a, const cut::BladePose& b, double time) {
  const double s = (time - a.time) / (b.time - a.time);
  return {time, a.tip + s * (b.tip - a.tip), a.heel + s * (b.heel - a.heel)};
}

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

absl::StatusOr<std::unique_ptr<Session>> Session::Create(std::string id, sim::Scene scene,
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
  std::unique_ptr<Session> session(new Session(std::move(id), options));
  session->scene_name_ = scene.name;
  for (const int level : scene.needs.levels()) {
    session->levels_.push_back(static_cast<kerf::v1::Level>(level));
  }
  if (session->levels_.empty()) {
    session->levels_ = {kerf::v1::SURFACE, kerf::v1::VOLUME, kerf::v1::FORCES};
  }
  absl::StatusOr<std::unique_ptr<sim::Simulation>> simulation =
      sim::Simulation::Create(std::move(scene));
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
  }
  session->thread_ = std::thread([s = session.get()] { s->Run(); });
  return session;
}

Session::~Session() { Close(absl::CancelledError(absl::StrCat("session ", id_, " closed"))); }

void Session::StopThread() {
  {
    absl::MutexLock lock(&mutex_);
    stopping_ = true;
  }
  if (thread_.joinable()) thread_.join();
}

void Session::Close(const absl::Status& why) {
  StopThread();
  std::vector<std::shared_ptr<Subscription>> ending;
  std::vector<SnapshotRequest*> snapshots;
  {
    absl::MutexLock lock(&mutex_);
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
  for (SnapshotRequest* request : snapshots) request->done.Notify();
  for (const auto& subscription : ending) {
    subscription->queue->Close();
    if (subscription->on_end) subscription->on_end(why);
  }
}

bool Session::Offers(kerf::v1::Level level) const {
  return std::find(levels_.begin(), levels_.end(), level) != levels_.end();
}

absl::StatusOr<std::shared_ptr<Subscription>> Session::Observe(
    kerf::v1::Level level, std::function<void(const SerializedFrame&)> start_write,
    std::function<void(const absl::Status&)> on_end) {
  if (level == kerf::v1::LEVEL_UNSPECIFIED || !kerf::v1::Level_IsValid(level)) {
    return absl::InvalidArgumentError("level must be SURFACE, VOLUME or FORCES");
  }
  if (!Offers(level)) {
    return absl::FailedPreconditionError(
        absl::StrCat("scene ", scene_name_, " does not offer ", kerf::v1::Level_Name(level)));
  }
  absl::MutexLock lock(&mutex_);
  if (stopping_) return absl::CancelledError(absl::StrCat("session ", id_, " closed"));
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
  if (!kerf::v1::Level_IsValid(level)) {
    return absl::InvalidArgumentError("level must be SURFACE, VOLUME or FORCES");
  }
  if (!Offers(level)) {
    return absl::FailedPreconditionError(
        absl::StrCat("scene ", scene_name_, " does not offer ", kerf::v1::Level_Name(level)));
  }
  if (!(frame_rate_hz >= 0 && frame_rate_hz <= options_.physics_rate_hz)) {
    return absl::InvalidArgumentError(
        absl::StrCat("frame_rate_hz must be between 0 (every tick) and the physics rate (",
                     options_.physics_rate_hz, " Hz), got ", frame_rate_hz));
  }
  absl::MutexLock lock(&mutex_);
  if (stopping_) return absl::CancelledError(absl::StrCat("session ", id_, " closed"));
  if (cutter_view_ != nullptr) {
    return absl::FailedPreconditionError(
        absl::StrCat("session ", id_, " already has a cutter; one at a time"));
  }
  const double frames_per_tick =
      frame_rate_hz == 0 ? 1.0 : frame_rate_hz / options_.physics_rate_hz;
  cutter_view_ = std::make_unique<View>(View{LevelView(level, *simulation_), frames_per_tick, {}});
  auto subscription = std::make_shared<Subscription>(Subscription{
      level, true, std::make_unique<FrameQueue>(options_.max_waiting_frames, start_write),
      std::move(on_end)});
  cutter_view_->subscribers.push_back(subscription);
  last_submitted_.reset();
  withdraw_when_done_ = false;
  on_withdrawn_ = nullptr;
  return subscription;
}

absl::Status Session::SubmitPose(const kerf::v1::BladePose& message) {
  absl::StatusOr<cut::BladePose> pose = cut::FromProto(message);
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
      cutter_view_.reset();
      withdraw_when_done_ = true;
      on_withdrawn_ = nullptr;
    }
    return;
  }
  auto& list = observer_views_[subscription->level]->subscribers;
  list.erase(std::remove(list.begin(), list.end(), subscription), list.end());
}

absl::StatusOr<kerf::v1::Frame> Session::Snapshot(kerf::v1::Level level, absl::Duration timeout) {
  if (level == kerf::v1::LEVEL_UNSPECIFIED || !kerf::v1::Level_IsValid(level)) {
    return absl::InvalidArgumentError("level must be SURFACE, VOLUME or FORCES");
  }
  if (!Offers(level)) {
    return absl::FailedPreconditionError(
        absl::StrCat("scene ", scene_name_, " does not offer ", kerf::v1::Level_Name(level)));
  }
  SnapshotRequest request;
  request.level = level;
  {
    absl::MutexLock lock(&mutex_);
    if (stopping_) return absl::CancelledError(absl::StrCat("session ", id_, " closed"));
    snapshots_.push_back(&request);
  }
  if (!request.done.WaitForNotificationWithTimeout(timeout)) {
    absl::MutexLock lock(&mutex_);
    const auto it = std::find(snapshots_.begin(), snapshots_.end(), &request);
    if (it != snapshots_.end()) {
      snapshots_.erase(it);
      return absl::DeadlineExceededError("the session did not reach a frame in time");
    }
  }
  request.done.WaitForNotification();  // taken by the tick or by Close
  if (!request.frame.has_statistics()) {
    return absl::CancelledError(absl::StrCat("session ", id_, " closed"));
  }
  return request.frame;
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
  info.set_vertices(simulation_->mesh().vertex_count());
  std::size_t observers = 0;
  for (const auto& view : observer_views_) observers += view->subscribers.size();
  info.set_observers(static_cast<std::uint32_t>(observers));
  info.set_cutting(cutter_view_ != nullptr);
  return info;
}

void Session::Run() {
  const absl::Duration period = absl::Seconds(tick_seconds_);
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

void Session::ApplyDuePoses(double until) {
  const auto apply = [&](const cut::BladePose& pose) {
    if (simulation_->ApplyBladePose(pose).ok()) {
      before_last_applied_ = last_applied_;
      last_applied_ = pose;
      ++poses_applied_;
    }
  };
  while (!poses_.empty() && poses_.front().time <= until) {
    apply(poses_.front());
    blade_time_ = poses_.front().time - pose_time_offset_;
    poses_.pop_front();
  }
  if (!poses_.empty() && last_applied_ && last_applied_->time < until) {
    apply(Interpolate(*last_applied_, poses_.front(), until));  // poses slower than ticks
  }
  if (poses_.empty() && withdraw_when_done_) {
    (void)simulation_->WithdrawBlade();
    withdraw_when_done_ = false;
    withdrawn_this_tick_ = true;
    last_applied_.reset();
    before_last_applied_.reset();
  }
}

void Session::Tick() {
  // Tick n ends at n periods of simulated time; steps of the scene's time step follow it.
  const double target = static_cast<double>(ticks_ + 1) * tick_seconds_;
  ApplyDuePoses(target);
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

  TickReport report;
  report.simulation_time = simulation_time_;
  report.blade_time = blade_time_;
  if (last_applied_) {
    const sim::ToolReaction reaction =
        sim::MeasureToolReaction(*simulation_, *last_applied_, before_last_applied_);
    report.tool_force = reaction.force;
    report.tool_torque = reaction.torque;
  }
  kerf::v1::StepStatistics& s = report.statistics;
  s.set_physics_steps(ticks_);
  s.set_physics_step_seconds(last_tick_seconds_);
  s.set_overruns(overruns_);
  s.set_tets(simulation_->mesh().tet_count());
  s.set_vertices(simulation_->mesh().vertex_count());
  s.set_cut_tets(simulation_->cutter() ? simulation_->cutter()->statistics().cut_tets : 0);
  s.set_poses_applied(poses_applied_);

  // The views that make a frame this tick; the nodal forces are computed once for them all.
  std::vector<std::pair<View*, bool>> due;  // and whether a snapshot waits for it
  for (auto& view : observer_views_) {
    const bool snapshot_pending =
        std::any_of(snapshots_.begin(), snapshots_.end(),
                    [&](const SnapshotRequest* r) { return r->level == view->frames.level(); });
    if (!view->DueAt(ticks_)) continue;
    if (view->subscribers.empty() && !snapshot_pending) continue;
    due.emplace_back(view.get(), snapshot_pending);
  }
  if (cutter_view_ != nullptr && (cutter_view_->DueAt(ticks_) || withdrawn_this_tick_)) {
    due.emplace_back(cutter_view_.get(), false);
  }
  std::vector<Eigen::Vector3d> nodal_forces;
  if (std::any_of(due.begin(), due.end(),
                  [](const auto& d) { return d.first->frames.level() == kerf::v1::FORCES; })) {
    nodal_forces = ComputeElasticForces(*simulation_);
    report.nodal_forces = nodal_forces;
  }
  for (const auto& [view, snapshot_pending] : due) Publish(*view, report, snapshot_pending);
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
}

void Session::Publish(View& view, const TickReport& report, bool snapshot_pending) {
  const kerf::v1::Frame frame = view.frames.Advance(report);
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
  if (!snapshot_pending) return;
  for (auto it = snapshots_.begin(); it != snapshots_.end();) {
    if ((*it)->level != view.frames.level()) {
      ++it;
      continue;
    }
    (*it)->frame = MakeSnapshot(view.frames.level(), *simulation_, original_vertex_bound_,
                                frame.sequence(), report);
    (*it)->frame.set_topology_version(frame.topology_version());
    (*it)->done.Notify();
    it = snapshots_.erase(it);
  }
}

}  // namespace kerf::service
