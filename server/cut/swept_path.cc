#include "cut/swept_path.h"

#include <algorithm>

#include "base/check.h"

namespace kerf::cut {

SweptPath::SweptPath(std::size_t capacity) : capacity_(std::max<std::size_t>(capacity, 2)) {}

void SweptPath::Add(const BladePose& pose) {
  if (!poses_.empty()) {
    const BladePose& a = poses_.back();
    const Box step{a.tip.cwiseMin(a.heel).cwiseMin(pose.tip).cwiseMin(pose.heel),
                   a.tip.cwiseMax(a.heel).cwiseMax(pose.tip).cwiseMax(pose.heel)};
    const std::size_t i = last();  // the step from the last pose to this one
    if (blocks_.empty() || i / kBlock > block_first_ + blocks_.size() - 1) {
      if (blocks_.empty()) block_first_ = i / kBlock;
      blocks_.push_back(step);
    } else {
      Box& block = blocks_.back();
      block.low = block.low.cwiseMin(step.low);
      block.high = block.high.cwiseMax(step.high);
    }
    steps_.push_back(step);
  }
  poses_.push_back(pose);
  if (poses_.size() > capacity_) {
    poses_.pop_front();
    steps_.pop_front();
    ++first_;
    while (!blocks_.empty() && (block_first_ + 1) * kBlock <= first_) {
      blocks_.pop_front();
      ++block_first_;
    }
  }
  KERF_CHECK(steps_.size() + 1 == poses_.size());
}

void SweptPath::ForEachStepNear(std::size_t from, std::size_t to, const Eigen::Vector3d& low,
                                const Eigen::Vector3d& high, double reach,
                                absl::FunctionRef<bool(std::size_t)> visit) const {
  from = std::max(from, first_);
  to = std::min(to, last());
  for (std::size_t i = from; i < to;) {
    const std::size_t block = i / kBlock;
    const std::size_t block_end = std::min(to, (block + 1) * kBlock);
    if (!blocks_[block - block_first_].Near(low, high, reach)) {
      i = block_end;
      continue;
    }
    for (; i < block_end; ++i) {
      if (steps_[i - first_].Near(low, high, reach) && !visit(i)) return;
    }
  }
}

}  // namespace kerf::cut
