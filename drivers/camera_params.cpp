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
  v.param("auto_exposure", p.auto_exposure,
          "the cameras choose their exposure (in dim water up to the frame period, smearing a "
          "moving marker); false sets exposure_time_us on both, and on the simulated cameras");
  v.param("exposure_time_us", p.exposure_time_us,
          {"us", 100, 1000000,
           "exposure time with auto_exposure false, in the camera's 100 us steps; its maximum is "
           "the smear budget: the marker's image speed times the exposure must stay under 1.35 "
           "sphere diameters (the bring-up guide's camera section), and it must fit in the "
           "frame period"});
  v.param("gain", p.gain,
          {"-", -1, 100000,
           "sensor gain (V4L2_CID_GAIN) in the camera's own units, checked against its range at "
           "open; -1 leaves it as the camera has it"});
  v.param("white_balance", p.white_balance,
          "auto: the cameras balance white themselves; lock: auto white balance off, at "
          "white_balance_temperature_k",
          {"auto", "lock"});
  v.param("white_balance_temperature_k", p.white_balance_temperature_k,
          {"K", 0, 15000,
           "white-balance temperature with white_balance lock; 0 locks the temperature the "
           "camera has at open"});
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
