// The vehicle's attitude as the pose tracker needs it: the body rates carry it from one read to
// the next and the attitude sensor pulls it back slowly, so the sensor's read-to-read noise (half a
// degree moves the marker by 7 mm at 0.8 m) does not reach the track.
#pragma once

#include <Eigen/Core>
#include <Eigen/Geometry>
#include <chrono>

namespace rovctl::control {

class AttitudeFilter {
 public:
  // correction_s: the time constant of the pull toward the attitude sensor (0: the sensor's
  // attitude as read). A read more than max_gap after the last starts afresh from the sensor.
  AttitudeFilter(double correction_s, std::chrono::nanoseconds max_gap);

  // One read at `now`. Not valid: the filter forgets (returns false). Rates that are not finite
  // leave the sensor's attitude to carry the filter alone.
  bool update(std::chrono::nanoseconds now, bool valid, const Eigen::Quaterniond& q_world_body,
              const Eigen::Vector3d& omega_body_radps);

  bool valid() const { return have_; }
  // The filtered attitude carried back or on to `at` by the last body rates (a frame captured a
  // tick before the read saw the vehicle as it was then).
  Eigen::Quaterniond q_world_body_at(std::chrono::nanoseconds at) const;

 private:
  double correction_s_;
  std::chrono::nanoseconds max_gap_;
  bool have_ = false;
  std::chrono::nanoseconds at_{0};
  Eigen::Quaterniond q_ = Eigen::Quaterniond::Identity();
  Eigen::Vector3d omega_radps_ = Eigen::Vector3d::Zero();
};

}  // namespace rovctl::control
