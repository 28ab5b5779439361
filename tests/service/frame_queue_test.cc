#include "service/frame_queue.h"

#include <gtest/gtest.h>

#include <vector>

namespace kerf::service {
namespace {

SerializedFrame MakeFrame(std::uint64_t sequence, bool topology) {
  return {std::make_shared<const std::string>("x"), sequence, topology, false};
}

struct Recorder {
  std::vector<std::uint64_t> written;
  FrameQueue queue{3, [this](const SerializedFrame& f) { written.push_back(f.sequence); }};
};

TEST(FrameQueue, StartsWithAKeyframeAndIgnoresDeltasUntilThen) {
  Recorder r;
  EXPECT_TRUE(r.queue.NeedsKeyframe());
  r.queue.Offer(MakeFrame(1, true));
  EXPECT_TRUE(r.written.empty());
  r.queue.OfferKeyframe({std::make_shared<const std::string>("k"), 1, true, true});
  EXPECT_EQ(r.written, std::vector<std::uint64_t>{1});
  EXPECT_FALSE(r.queue.NeedsKeyframe());
}

TEST(FrameQueue, WritesOneAtATimeAndPositionsAreLatestWins) {
  Recorder r;
  r.queue.OfferKeyframe(MakeFrame(0, true));
  r.queue.Offer(MakeFrame(1, false));  // waits: the keyframe is in flight
  r.queue.Offer(MakeFrame(2, false));  // replaces 1
  r.queue.Offer(MakeFrame(3, true));   // replaces 2 (which changed nothing)
  r.queue.Offer(MakeFrame(4, false));  // waits behind 3
  EXPECT_EQ(r.written, std::vector<std::uint64_t>{0});
  r.queue.WriteDone();
  r.queue.WriteDone();
  r.queue.WriteDone();
  EXPECT_EQ(r.written, (std::vector<std::uint64_t>{0, 3, 4}));
  EXPECT_EQ(r.queue.skipped(), 2u);
}

TEST(FrameQueue, NeverDropsTopologyButResyncsASubscriberThatFallsBehind) {
  Recorder r;
  r.queue.OfferKeyframe(MakeFrame(0, true));
  for (std::uint64_t s = 1; s <= 3; ++s) r.queue.Offer(MakeFrame(s, true));  // three wait
  EXPECT_FALSE(r.queue.NeedsKeyframe());
  r.queue.Offer(MakeFrame(4, true));  // a fourth would exceed the capacity: all dropped
  EXPECT_TRUE(r.queue.NeedsKeyframe());
  EXPECT_EQ(r.queue.resyncs(), 1u);
  r.queue.Offer(MakeFrame(5, true));  // ignored until the keyframe
  r.queue.WriteDone();
  EXPECT_EQ(r.written, std::vector<std::uint64_t>{0});
  r.queue.OfferKeyframe(MakeFrame(5, true));
  r.queue.WriteDone();
  EXPECT_EQ(r.written, (std::vector<std::uint64_t>{0, 5}));
}

TEST(FrameQueue, WritesNothingOnceClosed) {
  Recorder r;
  r.queue.OfferKeyframe(MakeFrame(0, true));
  r.queue.Offer(MakeFrame(1, true));
  r.queue.Close();
  r.queue.WriteDone();
  r.queue.Offer(MakeFrame(2, true));
  EXPECT_EQ(r.written, std::vector<std::uint64_t>{0});
  EXPECT_FALSE(r.queue.NeedsKeyframe());
}

}  // namespace
}  // namespace kerf::service
