// The blade's recent poses, numbered from 1 as they come, with the boxes of the steps between
// them grouped in blocks, so that the steps near a point or a tet are found without testing every
// step of a long path (a hand held in a tet for a second makes a thousand of them).
#pragma once

#include <Eigen/Core>
#include <cstddef>
#include <deque>

#include "absl/functional/function_ref.h"
#include "cut/blade.h"

namespace kerf::cut {

class SweptPath {
 public:
  // Keeps the last `capacity` poses (at least 2).
  explicit SweptPath(std::size_t capacity);

  // The next pose: number last() + 1.
  void Add(const BladePose& pose);
  // The oldest pose kept and the newest (last() < first() while there is none).
  std::size_t first() const { return first_; }
  std::size_t last() const { return first_ + poses_.size() - 1; }
  // Pose `i`, first() <= i <= last().
  const BladePose& at(std::size_t i) const { return poses_[i - first_]; }

  // Calls `visit(i)` for each step i (pose i to pose i + 1), from <= i < to, both kept, whose box
  // (its four points') comes within `reach` of the box from `low` to `high`, in order, until
  // `visit` returns false.
  void ForEachStepNear(std::size_t from, std::size_t to, const Eigen::Vector3d& low,
                       const Eigen::Vector3d& high, double reach,
                       absl::FunctionRef<bool(std::size_t)> visit) const;

 private:
  struct Box {
    Eigen::Vector3d low, high;
    bool Near(const Eigen::Vector3d& l, const Eigen::Vector3d& h, double reach) const {
      return ((low.array() - reach) <= h.array()).all() &&
             ((high.array() + reach) >= l.array()).all();
    }
  };
  static constexpr std::size_t kBlock = 64;  // steps per block

  std::size_t capacity_;
  std::size_t first_ = 1;
  std::deque<BladePose> poses_;
  std::deque<Box> steps_;   // step first_ + k at k
  std::deque<Box> blocks_;  // steps kBlock * (block_first_ + k) ... (a superset once popped)
  std::size_t block_first_ = 0;
};

}  // namespace kerf::cut
