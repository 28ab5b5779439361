// The poses a cutter has sent, to tell which one a frame answers. Frame.blade_time is the time
// of the last pose the session applied (0 before any); it went through the session's clock
// and back, so it equals the sent pose's time to within 1e-9 s. Thread-safe: the sender adds,
// the reader asks.
#pragma once

#include <array>
#include <map>
#include <optional>

#include "absl/base/thread_annotations.h"
#include "absl/synchronization/mutex.h"
#include "absl/time/time.h"
#include "kerf/v1/blade.pb.h"

namespace kerf::client {

class PoseLog {
 public:
  struct Answer {
    std::array<double, 3> tip;              // of the pose the frame answers, m
    std::optional<absl::Duration> latency;  // since it was sent: for the first frame only
  };

  // `pose` was sent at `when` (times increasing).
  void Sent(const kerf::v1::BladePose& pose, absl::Time when);
  // The pose a frame with this blade_time answers, received at `now`; nullopt when it answers
  // none this log sent. The poses sent before it are forgotten (no later frame answers them).
  std::optional<Answer> Answered(double blade_time, absl::Time now);

 private:
  struct Entry {
    std::array<double, 3> tip;
    absl::Time sent;
    bool answered = false;
  };
  absl::Mutex mutex_;
  std::map<double, Entry> sent_ ABSL_GUARDED_BY(mutex_);  // by pose time
};

}  // namespace kerf::client
