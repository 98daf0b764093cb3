// slamer-tfrog-sim --source-channel: the wheel_encoders_t messages another
// program publishes on an LCM channel (slamer-sim's SIM_WHEEL_ENCODERS) fed to
// an EncoderFollower (wheel_path.hpp), so the board's motors turn as the
// simulated robot's wheels did. Messages that do not decode or have fewer than
// two wheels are dropped with a one-line reason (first one, then a count at
// most every 5 s).
#pragma once

#include <lcm/lcm-cpp.hpp>

#include <cstdint>
#include <string>

#include "tools/tfrog_sim/wheel_path.hpp"

namespace slamer::tfrog {

class EncoderSource {
 public:
  // Throws std::runtime_error if LCM cannot be opened.
  EncoderSource(const std::string& lcm_url, const std::string& channel, EncoderFollower* follower);
  int fd() const { return fd_; }
  void pump();  // handles every message waiting

 private:
  static void on_message(const lcm::ReceiveBuffer* buffer, const std::string& channel, EncoderSource* self);
  void problem(const std::string& reason);

  lcm::LCM lcm_;
  int fd_ = -1;
  std::string channel_;
  EncoderFollower* follower_;
  int64_t problems_ = 0;
  int64_t last_log_us_ = 0;
};

}  // namespace slamer::tfrog
