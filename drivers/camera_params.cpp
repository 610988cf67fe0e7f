// Declarations (key, unit, range, meaning) of the camera parameters.
#include "drivers/camera_params.hpp"

namespace rovctl::drivers {

void describe(hal::ParamVisitor& v, V4l2CameraParams& p) {
  // Device names are not resolved against the config's folder: they are /dev paths or udev names.
  v.param("left_device", p.left_device,
          "left camera: a device path, or a name looked up in /dev/rovctl, /dev/v4l/by-id, "
          "/dev/v4l/by-path and /dev");
  v.param("right_device", p.right_device, "right camera: as left_device");
  v.param("width_px", p.width_px, {"px", 16, 7680, "image width (must match the calibration)"});
  v.param("height_px", p.height_px, {"px", 16, 4320, "image height (must match the calibration)"});
  v.param("fps", p.fps, {"Hz", 1, 240, "frame rate asked of both cameras"});
  v.param("format", p.format,
          "preferred pixel format; the other one is used if the camera "
          "lacks it",
          {"yuyv", "mjpg"});
  v.param("pairing_tolerance_ms", p.pairing_tolerance_ms,
          {"ms", 0.0, 1000.0, "largest left/right capture-stamp difference of a stereo pair"});
  v.param("buffer_count", p.buffer_count,
          {"-", 3, 10, "MMAP buffers per camera; buffer_count - 2 frames may wait for a partner"});
  v.param("grab_timeout_ms", p.grab_timeout_ms,
          {"ms", 1.0, 10000.0, "longest wait for a pair before grab() reports a timeout"});
  v.param("reopen_backoff_ms", p.reopen_backoff_ms,
          {"ms", 1.0, 60000.0, "wait before reopening a lost camera; doubles on each failure"});
  v.param("reopen_backoff_max_ms", p.reopen_backoff_max_ms,
          {"ms", 1.0, 600000.0, "longest wait between reopen attempts"});
}

void describe(hal::ParamVisitor& v, ReplayCameraParams& p) {
  v.path("path", p.path,
         "recorded-dive folder (frames.csv, left/, right/); or give left_video and right_video");
  v.path("left_video", p.left_video, "left video file (instead of path)");
  v.path("right_video", p.right_video, "right video file (instead of path)");
  v.param("mode", p.mode,
          "recorded: paced by the recorded stamps on the application's clock; tick: one pair "
          "per grab",
          {"recorded", "tick"});
  v.param("loop", p.loop, "start again at the end instead of reporting end of stream");
  v.param("fps", p.fps, {"Hz", 0.1, 1000.0, "frame rate of the video files (frame index timing)"});
}

void describe(hal::ParamVisitor& v, CameraParams& p) {
  v.param("backend", p.backend,
          "mock: rendered by the simulator; v4l2: two V4L2 cameras; replay: a recorded dive",
          {"mock", "v4l2", "replay"});
  v.section("v4l2", "two V4L2 cameras (used when backend is v4l2)",
            [&p](hal::ParamVisitor& s) { describe(s, p.v4l2); });
  v.section("replay", "recorded-dive playback (used when backend is replay)",
            [&p](hal::ParamVisitor& s) { describe(s, p.replay); });
}

}  // namespace rovctl::drivers
