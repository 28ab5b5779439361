#include "common/pose_log.h"

#include <cmath>

namespace kerf::client {

void PoseLog::Sent(const kerf::v1::BladePose& pose, absl::Time when) {
  absl::MutexLock lock(&mutex_);
  sent_[pose.time()] = {{pose.tip(0), pose.tip(1), pose.tip(2)}, when};
}

std::optional<PoseLog::Answer> PoseLog::Answered(double blade_time, absl::Time now) {
  if (blade_time == 0) return std::nullopt;  // no pose applied yet
  absl::MutexLock lock(&mutex_);
  const auto it = sent_.lower_bound(blade_time - 1e-9);
  if (it == sent_.end() || std::abs(it->first - blade_time) > 1e-9) return std::nullopt;
  Answer answer{it->second.tip, std::nullopt};
  if (!it->second.answered) answer.latency = now - it->second.sent;
  it->second.answered = true;
  sent_.erase(sent_.begin(), it);
  return answer;
}

}  // namespace kerf::client
