// The `camera` config section: which StereoCamera backend the application runs on, and the
// settings of each backend (V4L2 devices, recorded-dive replay).
#pragma once

#include <string>

#include "hal/primitives/parameters.hpp"

namespace rovctl::drivers {

struct V4l2CameraParams {
  std::string left_device = "/dev/rovctl/cam-left";  // path, or a udev name such as cam-left
  std::string right_device = "/dev/rovctl/cam-right";
  int width_px = 640;
  int height_px = 480;
  int fps = 30;
  std::string format = "yuyv";  // preferred pixel format: yuyv | mjpg (the other is the fallback)
  double pairing_tolerance_ms = 8.0;
  int buffer_count = 4;
  double grab_timeout_ms = 200.0;
  double reopen_backoff_ms = 250.0;
  double reopen_backoff_max_ms = 4000.0;
  // Camera controls, set on both cameras at open (drivers/v4l2/camera_controls). The exposure
  // also drives the simulated cameras' motion smear, so one setting flies in sim and on the rig.
  bool auto_exposure = true;
  int exposure_time_us = 4000;          // with auto_exposure off; the smear budget caps it
  int gain = -1;                        // -1: as the camera has it
  std::string white_balance = "auto";   // auto | lock
  int white_balance_temperature_k = 0;  // with lock; 0 locks the temperature the camera has
};

struct ReplayCameraParams {
  std::string path;               // a recorded-dive folder (deploy/recording-format.md)
  std::string left_video;         // or two video files, played by frame index at `fps`
  std::string right_video;        //
  std::string mode = "recorded";  // recorded: paced by the recorded stamps | tick: a pair per grab
  bool loop = false;
  double fps = 30.0;  // frame rate of the video files
};

struct CameraParams {
  std::string backend = "mock";  // mock | v4l2 | replay
  V4l2CameraParams v4l2;
  ReplayCameraParams replay;
};

void describe(hal::ParamVisitor& v, V4l2CameraParams& p);
void describe(hal::ParamVisitor& v, ReplayCameraParams& p);
void describe(hal::ParamVisitor& v, CameraParams& p);

}  // namespace rovctl::drivers
