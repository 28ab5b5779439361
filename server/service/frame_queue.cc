#include "service/frame_queue.h"

namespace kerf::service {

void FrameQueue::Push(const SerializedFrame& frame) {
  if (!waiting_.empty() && !waiting_.back().changes_topology && !waiting_.back().keyframe) {
    waiting_.back() = frame;  // latest wins
    ++skipped_;
    return;
  }
  if (waiting_.size() >= capacity_) {
    waiting_.clear();
    needs_keyframe_ = true;
    ++resyncs_;
    return;
  }
  waiting_.push_back(frame);
}

void FrameQueue::Offer(const SerializedFrame& frame) {
  {
    absl::MutexLock lock(&mutex_);
    if (closed_ || needs_keyframe_) return;
    Push(frame);
  }
  StartIfIdle();
}

void FrameQueue::OfferKeyframe(const SerializedFrame& frame) {
  {
    absl::MutexLock lock(&mutex_);
    if (closed_) return;
    waiting_.clear();
    waiting_.push_back(frame);
    needs_keyframe_ = false;
  }
  StartIfIdle();
}

void FrameQueue::StartIfIdle() {
  absl::MutexLock lock(&mutex_);
  if (writing_ || closed_ || waiting_.empty()) return;
  const SerializedFrame next = std::move(waiting_.front());
  waiting_.pop_front();
  writing_ = true;
  ++sent_;
  start_write_(next);
}

void FrameQueue::WriteDone() {
  {
    absl::MutexLock lock(&mutex_);
    writing_ = false;
  }
  StartIfIdle();
}

bool FrameQueue::NeedsKeyframe() const {
  absl::MutexLock lock(&mutex_);
  return needs_keyframe_ && !closed_;
}

void FrameQueue::Close() {
  absl::MutexLock lock(&mutex_);
  closed_ = true;
  waiting_.clear();
}

std::uint64_t FrameQueue::skipped() const {
  absl::MutexLock lock(&mutex_);
  return skipped_;
}

std::uint64_t FrameQueue::sent() const {
  absl::MutexLock lock(&mutex_);
  return sent_;
}

std::uint64_t FrameQueue::resyncs() const {
  absl::MutexLock lock(&mutex_);
  return resyncs_;
}

}  // namespace kerf::service
