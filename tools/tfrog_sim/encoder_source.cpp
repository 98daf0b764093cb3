#include "tools/tfrog_sim/encoder_source.hpp"

#include <cstdio>
#include <stdexcept>

#include "common/process/decode.hpp"
#include "common/process/lcm_bus.hpp"
#include "slamer/wheel_encoders_t.hpp"

namespace slamer::tfrog {

EncoderSource::EncoderSource(const std::string& lcm_url, const std::string& channel, EncoderFollower* follower)
    : lcm_(lcm_url), channel_(channel), follower_(follower) {
  if (!lcm_.good()) {
    throw std::runtime_error("cannot open LCM" + (lcm_url.empty() ? std::string() : " URL '" + lcm_url + "'"));
  }
  lcm_.subscribeFunction(literal_pattern(channel), &EncoderSource::on_message, this);
  fd_ = lcm_.getFileno();
}

void EncoderSource::pump() {
  while (lcm_.handleTimeout(0) > 0) {
  }
}

void EncoderSource::problem(const std::string& reason) {
  const int64_t now = now_utime();
  if (++problems_ == 1 || now - last_log_us_ >= 5000000) {
    std::fprintf(stderr, "slamer-tfrog-sim: %s: message dropped (%lld so far): %s\n", channel_.c_str(),
                 static_cast<long long>(problems_), reason.c_str());
    last_log_us_ = now;
  }
}

void EncoderSource::on_message(const lcm::ReceiveBuffer* buffer, const std::string&, EncoderSource* self) {
  wheel_encoders_t message;
  const DecodeStatus status = decode_message(buffer->data, buffer->data_size, &message);
  if (status != DecodeStatus::kOk) {
    self->problem("not a wheel_encoders_t (" + std::string(describe(status)) + ")");
  } else if (message.nwheels < 2) {
    self->problem("nwheels " + std::to_string(message.nwheels) + ", want 2 (left, right)");
  } else {
    self->follower_->add(message.utime, message.ticks[0], message.ticks[1]);
  }
}

}  // namespace slamer::tfrog
