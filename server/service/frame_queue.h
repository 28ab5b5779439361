// One subscriber's frames on their way out: the session offers each frame once (serialized
// once for all subscribers of its view), the network writes one at a time.
//
// Never blocks the offering thread. While a write is in flight, frames wait; a waiting frame
// that changes no topology is replaced by the next one (positions are latest-wins), and when
// more than `capacity` frames wait the subscriber has fallen behind: they are dropped and it
// is marked to receive a fresh keyframe, so that no topology change is ever lost.
#pragma once

#include <cstdint>
#include <deque>
#include <functional>
#include <memory>
#include <string>

#include "absl/base/thread_annotations.h"
#include "absl/synchronization/mutex.h"

namespace kerf::service {

struct SerializedFrame {
  std::shared_ptr<const std::string> bytes;
  std::uint64_t sequence = 0;
  bool changes_topology = false;
  bool keyframe = false;
};

class FrameQueue {
 public:
  // `start_write` is called with each frame to write, under the queue's lock (so that after
  // Close() returns it is never called again; it must not call back into the queue); the
  // writer calls WriteDone() when the write completes.
  FrameQueue(std::size_t capacity, std::function<void(const SerializedFrame&)> start_write)
      : capacity_(capacity), start_write_(std::move(start_write)) {}

  // Offers a delta. Ignored while the subscriber waits for a keyframe.
  void Offer(const SerializedFrame& frame);
  // Offers a keyframe (after NeedsKeyframe): it replaces whatever waits.
  void OfferKeyframe(const SerializedFrame& frame);
  void WriteDone();

  // Whether the subscriber must be sent a keyframe (at the start, and after falling behind).
  bool NeedsKeyframe() const;
  // Stops writing: later offers are ignored.
  void Close();

  // Counters, for statistics and tests.
  std::uint64_t skipped() const;  // frames replaced by a later one (latest wins)
  std::uint64_t resyncs() const;  // times it fell behind and was given a keyframe
  std::uint64_t sent() const;     // frames handed to the writer

 private:
  void Push(const SerializedFrame& frame) ABSL_EXCLUSIVE_LOCKS_REQUIRED(mutex_);
  void StartIfIdle() ABSL_LOCKS_EXCLUDED(mutex_);

  const std::size_t capacity_;
  const std::function<void(const SerializedFrame&)> start_write_;
  mutable absl::Mutex mutex_;
  std::deque<SerializedFrame> waiting_ ABSL_GUARDED_BY(mutex_);
  bool writing_ ABSL_GUARDED_BY(mutex_) = false;
  bool needs_keyframe_ ABSL_GUARDED_BY(mutex_) = true;
  bool closed_ ABSL_GUARDED_BY(mutex_) = false;
  std::uint64_t skipped_ ABSL_GUARDED_BY(mutex_) = 0;
  std::uint64_t resyncs_ ABSL_GUARDED_BY(mutex_) = 0;
  std::uint64_t sent_ ABSL_GUARDED_BY(mutex_) = 0;
};

}  // namespace kerf::service
