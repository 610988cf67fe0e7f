// Construction helpers for simulated and default rigs.
#include "hal/model/stereo_rig.hpp"

namespace rovctl::hal {

StereoRig make_parallel_rig(const CameraModel& camera, double baseline_m, double toe_in_rad) {
  StereoRig rig;
  rig.left = camera;
  rig.right = camera;
  // The right camera sits at +x of the left; toe-in turns both optical axes toward each other
  // (left yaws right, right yaws left), so the right camera is rotated by -2*toe about y.
  const Eigen::AngleAxisd R_cl_cr(-2.0 * toe_in_rad, Eigen::Vector3d::UnitY());
  Eigen::Isometry3d T_cl_cr = Eigen::Isometry3d::Identity();
  T_cl_cr.linear() = R_cl_cr.toRotationMatrix();
  T_cl_cr.translation() = Eigen::Vector3d(baseline_m, 0.0, 0.0);
  rig.T_cr_cl = T_cl_cr.inverse();
  return rig;
}

}  // namespace rovctl::hal
