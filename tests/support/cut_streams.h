// Cut streams of the service tests: a start, poses at once, a straight cut across the bar.
#pragma once

#include <grpcpp/grpcpp.h>

#include <Eigen/Core>
#include <algorithm>
#include <cstdint>
#include <string>
#include <vector>

#include "kerf/v1/simulator.grpc.pb.h"
#include "support/service_bar.h"
#include "support/test_server.h"

namespace kerf::testing {

// Reads a stream to its end; its status.
template <typename Stream>
grpc::Status DrainAndFinish(Stream& stream) {
  kerf::v1::Frame frame;
  while (stream.Read(&frame)) {
  }
  return stream.Finish();
}

// The first message of a cut stream.
inline kerf::v1::CutRequest CutStart(const std::string& session, const std::string& token) {
  kerf::v1::CutRequest start;
  start.mutable_start()->set_session_id(session);
  start.mutable_start()->set_token(token);
  return start;
}

// A cut stream that sends its start, then `poses` at once, then ends: its status.
inline grpc::Status CutWith(kerf::v1::Simulator::Stub& stub, const std::string& session,
                            const std::string& token,
                            const std::vector<kerf::v1::BladePose>& poses) {
  grpc::ClientContext context;
  auto stream = stub.Cut(&context);
  stream->Write(CutStart(session, token));
  for (const kerf::v1::BladePose& pose : poses) {
    kerf::v1::CutRequest request;
    *request.mutable_pose() = pose;
    stream->Write(request);
  }
  stream->WritesDone();
  return DrainAndFinish(*stream);
}

inline kerf::v1::BladePose Pose(double time, double y) { return BarBladePose(time, y); }

// Streams a straight cut across the bar at x = 23.7 mm, 2 mm per pose, 100 poses per second.
// Sends 16 poses 10 ms apart (slower than the 1 kHz ticks, so the session interpolates).
// `largest_force`, if given, receives the largest tool force of the frames (N), and
// `poses_applied` what the last frame reports.
inline grpc::Status CutAcross(kerf::v1::Simulator::Stub& stub, const std::string& session,
                              int* frames, double* largest_force = nullptr,
                              std::uint64_t* poses_applied = nullptr) {
  grpc::ClientContext context;
  auto stream = stub.Cut(&context);
  kerf::v1::CutRequest start = CutStart(session, TokensOf(session).cutter);
  start.mutable_start()->set_level(kerf::v1::FORCES);
  start.mutable_start()->set_frame_rate_hz(100);
  stream->Write(start);
  for (int k = 0; k <= 15; ++k) {
    kerf::v1::CutRequest request;
    *request.mutable_pose() = Pose(0.01 * k, -0.005 + 0.002 * k);
    stream->Write(request);
  }
  stream->WritesDone();
  kerf::v1::Frame frame;
  while (stream->Read(&frame)) {
    ++*frames;
    const Eigen::Vector3d f(frame.tool_force().x(), frame.tool_force().y(), frame.tool_force().z());
    if (largest_force != nullptr) *largest_force = std::max(*largest_force, f.norm());
    if (poses_applied != nullptr) *poses_applied = frame.statistics().poses_applied();
  }
  return stream->Finish();
}
}  // namespace kerf::testing
