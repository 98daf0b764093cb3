#include "localizer/localizer_messages.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <iterator>

#include "slamer/process_status_t.hpp"

namespace slamer {

int8_t to_status(LocalizerStatus status) {
  switch (status) {
    case LocalizerStatus::kInitializing:
      return pose_estimate_t::INITIALIZING;
    case LocalizerStatus::kOk:
      return pose_estimate_t::OK;
    case LocalizerStatus::kUncertain:
      return pose_estimate_t::UNCERTAIN;
    case LocalizerStatus::kLost:
      return pose_estimate_t::LOST;
  }
  return pose_estimate_t::LOST;
}

pose_estimate_t to_pose_message(const UpdateResult& result, int64_t utime, int particles) {
  pose_estimate_t message;
  message.utime = utime;
  message.x = result.estimate.pose.x;
  message.y = result.estimate.pose.y;
  message.theta = result.estimate.pose.theta;
  std::copy(std::begin(result.estimate.covariance), std::end(result.estimate.covariance), std::begin(message.cov));
  message.nparticles = particles;
  message.ess = result.estimate.ess;
  message.status = to_status(result.estimate.status);
  return message;
}

particles_t to_particles_message(const std::vector<Particle>& particles, int64_t utime, int count) {
  particles_t message;
  message.utime = utime;
  const std::size_t n = std::min(particles.size(), static_cast<std::size_t>(std::max(count, 0)));
  for (std::size_t i = 0; i < n; ++i) {
    const Particle& p = particles[i * particles.size() / n];
    message.x.push_back(p.pose.x);
    message.y.push_back(p.pose.y);
    message.theta.push_back(p.pose.theta);
    message.weight.push_back(std::exp(p.log_weight));
  }
  message.n = static_cast<int32_t>(n);
  return message;
}

std::pair<int8_t, std::string> process_state(LocalizerStatus status, const std::string& reason,
                                             const InputHealth& health, const LocalizerChannels& channels) {
  std::string message;
  const auto add = [&](const std::string& part) { message += (message.empty() ? "" : "; ") + part; };
  const auto missing = [&](const std::string& channel, double age, const std::string& consequence) {
    char text[32];
    std::snprintf(text, sizeof text, "%.1f s", age);
    add("no " + channel + (std::isfinite(age) ? " for " + std::string(text) : " yet") + ": " + consequence);
  };
  if (status == LocalizerStatus::kLost) {
    add("lost: " + reason);
  } else if (status == LocalizerStatus::kUncertain) {
    add("uncertain: " + reason);
  }
  if (health.odometry_missing) {
    missing(channels.odometry, health.odometry_age, "following the scans alone");
  }
  if (health.objects_missing) {
    missing(channels.line_objects, health.objects_age, "geometry only");
  }
  if (status == LocalizerStatus::kLost) {
    return {process_status_t::ERROR, message};
  }
  return {message.empty() ? process_status_t::OK : process_status_t::DEGRADED, message};
}

std::string describe(const initial_pose_t& m) {
  char text[160];
  std::snprintf(text, sizeof text, "(%.3f, %.3f, %.3f), sigma (%.3g, %.3g, %.3g)", m.x, m.y, m.theta,
                std::sqrt(m.cov[0]), std::sqrt(m.cov[4]), std::sqrt(m.cov[8]));
  return text;
}

}  // namespace slamer
