// `rovctl record`: saves timestamped stereo pairs from the configured camera backend as a
// recorded dive (deploy/recording-format.md) that the replay backend plays back.
#include <csignal>
#include <filesystem>
#include <iostream>
#include <memory>

#include "app/cli/cli_args.hpp"
#include "app/cli/commands.hpp"
#include "app/runtime/app_config.hpp"
#include "app/runtime/errors.hpp"
#include "app/runtime/vehicle_backends.hpp"
#include "app/tools/output_folder.hpp"
#include "drivers/camera_factory.hpp"
#include "drivers/monotonic_clock.hpp"
#include "drivers/replay/dive_recorder.hpp"

namespace rovctl::app {

namespace {

volatile std::sig_atomic_t g_stop = 0;

extern "C" void request_stop(int) { g_stop = 1; }

// Ctrl-C or systemd's SIGTERM end a recording cleanly: the last pair is complete on disk.
class StopOnSignal {
 public:
  StopOnSignal() {
    g_stop = 0;
    struct sigaction sa {};
    sa.sa_handler = request_stop;
    sigemptyset(&sa.sa_mask);
    sigaction(SIGINT, &sa, &old_int_);
    sigaction(SIGTERM, &sa, &old_term_);
  }
  ~StopOnSignal() {
    sigaction(SIGINT, &old_int_, nullptr);
    sigaction(SIGTERM, &old_term_, nullptr);
  }
  StopOnSignal(const StopOnSignal&) = delete;
  StopOnSignal& operator=(const StopOnSignal&) = delete;
  bool requested() const { return g_stop != 0; }

 private:
  struct sigaction old_int_ {};
  struct sigaction old_term_ {};
};

}  // namespace

int command_record(const Words& words) {
  const CliArgs args = CliArgs::parse("record", words, {"--config", "--out", "--frames"}, {});
  if (!args.has("--config")) throw UsageError("rovctl record: --config FILE is required");
  if (!args.has("--out")) throw UsageError("rovctl record: --out DIR is required");
  // 0: until the stream ends, Ctrl-C or SIGTERM.
  const long frames_wanted = args.get_int("--frames", 0, 1, 100000000);
  const std::string out = args.get("--out");
  const AppConfig config = load_app_config(args.get("--config"));
  prepare_output_folder("record", out);  // before the camera is opened

  // The mock camera records the simulated world (in real time) at its start pose.
  VehicleBackends hw = make_vehicle_backends(config, load_rig(config));
  hal::Clock& clock = *hw.clock;
  hal::StereoCamera* camera = hw.camera;
  std::string error;
  if (!camera->open(error)) throw ConfigError(error);
  const std::string camera_name = camera->name();  // with what open() negotiated
  std::cerr << "rovctl record: " << camera_name << "\n";

  std::string calibration = config.calibration_file;
  std::error_code ec;
  if (!calibration.empty() && !std::filesystem::is_regular_file(calibration, ec)) {
    std::cerr << "rovctl record: warning: calibration " << calibration
              << " not found, the recording will not include it\n";
    calibration.clear();
  }
  drivers::DiveRecorder recorder;
  if (!recorder.open(out, calibration, error)) throw UsageError("rovctl record: --out " + error);

  const StopOnSignal stop;
  hal::StereoFrame frame;
  std::size_t timeouts = 0;
  std::size_t losses = 0;
  bool lost = false;
  bool ended = false;
  while (!stop.requested() && (frames_wanted == 0 || recorder.frames_written() <
                                                         static_cast<std::size_t>(frames_wanted))) {
    const hal::GrabStatus status = camera->grab(frame);
    if (status == hal::GrabStatus::ok) {
      lost = false;
      if (!recorder.write(frame, error)) {
        std::cerr << "rovctl record: " << error << "\n";
        return kExitRuntimeFailure;
      }
    } else if (status == hal::GrabStatus::end_of_stream) {
      ended = true;
      break;
    } else if (status == hal::GrabStatus::timeout) {
      ++timeouts;
    } else {
      if (!lost) {
        ++losses;
        std::cerr << "rovctl record: camera lost, retrying: " << camera_name << "\n";
      }
      lost = true;
      // The camera reopens itself with back-off; do not spin while it waits.
      clock.sleep_until(clock.now() + std::chrono::milliseconds(50));
    }
  }
  camera->close();
  recorder.close();
  std::cout << "rovctl record: " << recorder.frames_written() << " stereo pairs from "
            << camera_name << " into " << out << " (" << timeouts << " timeouts, " << losses
            << " device losses" << (ended ? ", end of stream" : "")
            << (stop.requested() ? ", stopped by signal" : "") << ")\n";
  return recorder.frames_written() > 0 ? kExitOk : kExitRuntimeFailure;
}

}  // namespace rovctl::app
