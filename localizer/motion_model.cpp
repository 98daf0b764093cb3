#include "localizer/motion_model.hpp"

#include <algorithm>
#include <cmath>

namespace slamer {

OdometryIncrement decompose(const Pose2& from, const Pose2& to) {
  const double dx = to.x - from.x;
  const double dy = to.y - from.y;
  const double trans = std::hypot(dx, dy);
  // Below 1 mm the direction of travel is noise: all of the turn is rot2.
  const double rot1 = trans < 1e-3 ? 0.0 : angle_diff(std::atan2(dy, dx), from.theta);
  // A base that reversed moves against its heading: keep rot1 small, translate backwards.
  if (std::abs(rot1) > M_PI / 2) {
    const double back = angle_diff(rot1, M_PI);
    return {back, -trans, angle_diff(angle_diff(to.theta, from.theta), back)};
  }
  return {rot1, trans, angle_diff(angle_diff(to.theta, from.theta), rot1)};
}

namespace {

// Below these the wheels stood still: a base that does not move does not slip.
constexpr double kMovingTrans = 1e-4;  // [m]
constexpr double kMovingTurn = 1e-4;   // [rad]

}  // namespace

Pose2 sample_motion(const Pose2& pose, const OdometryIncrement& u, const MotionOptions& o, std::mt19937& rng,
                    double gain, double seconds) {
  const double trans = std::abs(u.trans);
  // The floor enters only as the gain rises above 1 (the scan fit fell): a
  // filter that explains its scans keeps the configured noise exactly. It is
  // a random walk: its variance grows with the time between scans, so a
  // 40 Hz scanner's particles spread as fast per second as a 4 Hz one's, not
  // sqrt(10) times faster. Scans further apart than noise_floor_interval get
  // the whole floor and no more: there the alphas, which grow with the
  // increment, carry the noise.
  const double share = std::sqrt(std::clamp(seconds / o.noise_floor_interval, 0.0, 1.0));
  const double floor_trans = (gain - 1.0) * o.noise_floor_trans * share;
  const double floor_rot = (gain - 1.0) * o.noise_floor_rot * share;
  const double sd_rot1 = gain * (o.alpha_rot_from_rot * std::abs(u.rot1) + o.alpha_rot_from_trans * trans);
  const double sd_trans =
      gain * (o.alpha_trans_from_trans * trans + o.alpha_trans_from_rot * (std::abs(u.rot1) + std::abs(u.rot2))) +
      floor_trans;
  const double sd_rot2 = gain * (o.alpha_rot_from_rot * std::abs(u.rot2) + o.alpha_rot_from_trans * trans) + floor_rot;
  std::normal_distribution<double> standard(0.0, 1.0);
  const double rot1 = u.rot1 + sd_rot1 * standard(rng);
  const double t = u.trans + sd_trans * standard(rng);
  double rot2 = u.rot2 + sd_rot2 * standard(rng);
  // No draw without a slip fraction, so a configuration without it keeps its random sequence.
  const bool moving = trans > kMovingTrans || std::abs(u.rot1 + u.rot2) > kMovingTurn;
  if (o.heading_slip_fraction > 0.0 && moving) {
    std::uniform_real_distribution<double> unit(0.0, 1.0);
    if (unit(rng) < o.heading_slip_fraction) {
      rot2 += o.heading_slip_sigma * standard(rng);
    }
  }
  const double heading = pose.theta + rot1;
  return {pose.x + t * std::cos(heading), pose.y + t * std::sin(heading), wrap_angle(heading + rot2)};
}

}  // namespace slamer
