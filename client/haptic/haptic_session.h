// kerf-haptic's work: one device drives the blade of one session. Three threads:
//   - the force loop (default 1 kHz): samples the device, renders the force of the local
//     model (ForceModel) and records its own timing; it only ever try-locks what it shares
//     with the network, so it never waits for it;
//   - the sender: streams the device's latest pose to Cut at `pose_rate_hz`;
//   - the reader: takes the cutter's frames and hands their forces to the loop.
// A stream that breaks with UNAVAILABLE (a server restart) is reopened with exponential
// backoff (0.1 s doubling to 5 s, 8 attempts), and the cut goes on.
#pragma once

#include <memory>
#include <string>
#include <vector>

#include "absl/status/statusor.h"
#include "haptic/force_model.h"
#include "haptic/haptic_device.h"
#include "kerf/v1/simulator.grpc.pb.h"

namespace kerf::client {

struct HapticOptions {
  std::string session_id;  // the session to cut in
  std::string cutter_token;
  double loop_rate_hz = 1000;
  double pose_rate_hz = 250;
  double cutter_frame_rate_hz = 0;  // asked of the server; 0: every physics tick
  double frame_delay_seconds = 0;   // each frame used this long after it came (a slow network)
  double max_seconds = 600;         // the device is stopped after this long
  ForceModel::Options force;
};

// What was measured, per force-loop tick and per frame (times on the loop's clock, s).
struct HapticRecord {
  std::vector<double> tick_times;
  std::vector<double> force_jumps;  // |F_k - F_{k-1}| between ticks, N
  std::vector<double> frame_times;
  std::vector<double> latencies;    // pose-to-frame, s, for frames that answer a pose
  std::uint64_t frames_missed = 0;  // gaps in the frames' sequence numbers
  std::uint64_t reconnects = 0;
  double largest_force = 0;  // N
  std::string error;         // empty, or why the cut ended early
};

// Runs until the device is done (or max_seconds), then withdraws the blade.
HapticRecord RunHaptic(kerf::v1::Simulator::Stub& stub, HapticDevice& device,
                       const HapticOptions& options);

}  // namespace kerf::client
