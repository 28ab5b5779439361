// What a client rebuilds from a session's frames (a keyframe and deltas, see frame.proto), and
// an observer that keeps what it rebuilt at each frame, on its own thread.
#pragma once

#include <grpcpp/grpcpp.h>
#include <gtest/gtest.h>

#include <algorithm>
#include <cstdint>
#include <map>
#include <optional>
#include <set>
#include <string>
#include <thread>
#include <vector>

#include "absl/strings/str_cat.h"
#include "absl/synchronization/mutex.h"
#include "absl/time/time.h"
#include "kerf/v1/frame.pb.h"
#include "support/test_server.h"

namespace kerf::testing {

// What a client rebuilds from a keyframe and deltas.
struct RebuiltView {
  std::set<std::uint32_t> vertices;
  std::map<std::uint32_t, std::vector<std::uint32_t>> elements;
  std::map<std::uint32_t, bool> on_cut;
  std::string positions, forces;
  std::uint64_t topology_version = 0;

  // Applies a frame; false (with a message) when it does not fit what came before.
  bool Apply(const kerf::v1::Frame& f, std::string* error) {
    if (f.keyframe()) {
      vertices.clear();
      elements.clear();
      on_cut.clear();
    } else if (f.topology_version() != topology_version &&
               f.topology_version() != topology_version + 1) {
      *error = absl::StrCat("topology ", f.topology_version(), " after ", topology_version);
      return false;
    }
    topology_version = f.topology_version();
    for (const std::uint32_t v : f.removed_vertices()) vertices.erase(v);
    for (const std::uint32_t v : f.added_vertices()) vertices.insert(v);
    for (const std::uint32_t e : f.removed_elements()) {
      elements.erase(e);
      on_cut.erase(e);
    }
    const int corners = f.level() == kerf::v1::VOLUME ? 4 : 3;
    for (int i = 0; i < f.added_elements_size(); ++i) {
      elements[f.added_elements(i)] = {f.added_element_vertices().begin() + corners * i,
                                       f.added_element_vertices().begin() + corners * (i + 1)};
      if (f.level() == kerf::v1::SURFACE)
        on_cut[f.added_elements(i)] = f.added_elements_on_cut()[i];
    }
    positions = f.positions();
    forces = f.nodal_forces();
    const std::size_t bytes = 12 * vertices.size();
    if ((f.level() == kerf::v1::FORCES ? forces.size() : positions.size()) != bytes) {
      *error =
          absl::StrCat("array of ", positions.size(), " bytes for ", vertices.size(), " vertices");
      return false;
    }
    return true;
  }

  // Triangles as rotation-normalised triples with their cut flag (ids are the view's own).
  std::multiset<std::vector<std::uint32_t>> Triangles() const {
    std::multiset<std::vector<std::uint32_t>> out;
    for (const auto& [id, v] : elements) {
      std::vector<std::uint32_t> t = v;
      std::rotate(t.begin(), std::min_element(t.begin(), t.end()), t.end());
      t.push_back(on_cut.count(id) ? on_cut.at(id) : 0);
      out.insert(t);
    }
    return out;
  }
};

// An observer on its own thread, keeping what it rebuilt at each sequence number.
class Observer {
 public:
  // `stall`: how long it waits before reading (a slow client).
  Observer(kerf::v1::Simulator::Stub& stub, const std::string& session, kerf::v1::Level level,
           absl::Duration stall = absl::ZeroDuration()) {
    kerf::v1::ObserveRequest request;
    request.set_session_id(session);
    request.set_level(level);
    request.set_token(TokensOf(session).observer);
    reader_ = stub.Observe(&context_, request);
    thread_ = std::thread([this, stall] {
      absl::SleepFor(stall);
      kerf::v1::Frame frame;
      RebuiltView view;
      while (reader_->Read(&frame)) {
        std::string error;
        absl::MutexLock lock(&mutex_);
        if (frames_ == 0) first_was_keyframe_ = frame.keyframe();
        if (frames_ > 0 && !frame.keyframe() && frame.sequence() > last_sequence_ + 1) ++gaps_;
        ++frames_;
        if (!view.Apply(frame, &error)) errors_.push_back(error);
        if (frame.keyframe()) ++keyframes_;
        by_sequence_[frame.sequence()] = view;
        last_sequence_ = frame.sequence();
      }
      const grpc::Status status = reader_->Finish();
      absl::MutexLock lock(&mutex_);
      status_ = status;
      finished_ = true;
    });
  }
  ~Observer() { Stop(); }
  void Stop() {
    context_.TryCancel();
    if (thread_.joinable()) thread_.join();
  }
  // Waits (up to 10 s) until a frame with at least this sequence came; the view at exactly it.
  std::optional<RebuiltView> At(std::uint64_t sequence) {
    absl::MutexLock lock(&mutex_);
    const auto reached = [&]() ABSL_EXCLUSIVE_LOCKS_REQUIRED(mutex_) {
      return last_sequence_ >= sequence;
    };
    mutex_.AwaitWithTimeout(absl::Condition(&reached), absl::Seconds(10));
    const auto it = by_sequence_.find(sequence);
    if (it == by_sequence_.end()) return std::nullopt;
    return it->second;
  }
  std::vector<std::string> errors() {
    absl::MutexLock lock(&mutex_);
    return errors_;
  }
  int keyframes() {
    absl::MutexLock lock(&mutex_);
    return keyframes_;
  }
  int gaps() {
    absl::MutexLock lock(&mutex_);
    return gaps_;
  }
  bool first_was_keyframe() {
    absl::MutexLock lock(&mutex_);
    return first_was_keyframe_;
  }
  // The stream's end status, once the server ended it (within 10 s).
  std::optional<grpc::Status> EndStatus() {
    absl::MutexLock lock(&mutex_);
    mutex_.AwaitWithTimeout(absl::Condition(&finished_), absl::Seconds(10));
    if (!finished_) return std::nullopt;
    return status_;
  }

 private:
  grpc::ClientContext context_;
  std::unique_ptr<grpc::ClientReader<kerf::v1::Frame>> reader_;
  std::thread thread_;
  absl::Mutex mutex_;
  std::map<std::uint64_t, RebuiltView> by_sequence_;
  std::uint64_t last_sequence_ = 0;
  std::vector<std::string> errors_;
  int keyframes_ = 0;
  int frames_ = 0;
  int gaps_ = 0;
  bool first_was_keyframe_ = false;
  bool finished_ = false;
  grpc::Status status_;
};

// What the observer rebuilt at the snapshot's sequence equals the snapshot.
inline void ExpectSeesSnapshot(Observer& observer, const kerf::v1::Frame& snapshot) {
  RebuiltView expected;
  std::string error;
  ASSERT_TRUE(expected.Apply(snapshot, &error)) << error;
  const std::optional<RebuiltView> seen = observer.At(snapshot.sequence());
  ASSERT_TRUE(seen.has_value()) << "no frame " << snapshot.sequence();
  const std::vector<std::string> errors = observer.errors();
  EXPECT_TRUE(errors.empty()) << errors.front();
  EXPECT_EQ(seen->vertices, expected.vertices);
  EXPECT_EQ(seen->positions, expected.positions);
  EXPECT_EQ(seen->forces, expected.forces);
  if (snapshot.level() == kerf::v1::VOLUME) {
    EXPECT_EQ(seen->elements, expected.elements);
  }
  if (snapshot.level() == kerf::v1::SURFACE) {
    EXPECT_EQ(seen->Triangles(), expected.Triangles());
  }
}
}  // namespace kerf::testing
