// The one validation every command goes through before a device is opened: each bad layout,
// marker, calibration and contact source is a ConfigError naming file, line and key; a contact
// switch no backend reports becomes vision contact with a warning.
#include "app/runtime/config_validation.hpp"

#include <gtest/gtest.h>
#include <unistd.h>

#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>

#include "app/runtime/app_config.hpp"
#include "app/runtime/errors.hpp"
#include "app/runtime/vehicle_backends.hpp"

namespace rovctl::app {
namespace {

namespace fs = std::filesystem;

const std::string kCalibration =
    std::string(ROVCTL_SOURCE_DIR) + "/deploy/config/stereo_calibration.yaml";

struct TempDir {
  fs::path dir = fs::temp_directory_path() / ("rovctl_validation_" + std::to_string(::getpid()));
  TempDir() { fs::create_directories(dir); }
  ~TempDir() { fs::remove_all(dir); }
  std::string write(const std::string& name, const std::string& text) const {
    std::ofstream(dir / name) << text;
    return (dir / name).string();
  }
  // The shipped calibration with one text replaced.
  std::string calibration(const std::string& name, const std::string& from,
                          const std::string& to) const {
    std::ifstream in(kCalibration);
    std::stringstream s;
    s << in.rdbuf();
    std::string text = s.str();
    const std::size_t at = text.find(from);
    EXPECT_NE(at, std::string::npos) << from;
    if (at != std::string::npos) text.replace(at, from.size(), to);
    return write(name, text);
  }
};

// The error of loading `config` and its calibration, as every command does; "" when accepted.
std::string validation_error_of(const std::string& config) {
  try {
    const AppConfig c = load_app_config(config);
    load_rig(c);
  } catch (const ConfigError& e) {
    return e.what();
  }
  return "";
}

TEST(ConfigValidation, TheShippedConfigsPassWithoutWarnings) {
  for (const char* name : {"sim.yaml", "sim-ardusub.yaml", "vehicle.yaml", "bluerov2-heavy.yaml"}) {
    const std::string file = std::string(ROVCTL_SOURCE_DIR) + "/deploy/config/" + name;
    const AppConfig c = load_app_config(file);
    EXPECT_NO_THROW(load_rig(c)) << name;
    for (const std::string& w : c.warnings) ADD_FAILURE() << name << ": " << w;
  }
}

TEST(ConfigValidation, ALayoutThatCannotPushAServoAxisIsRejectedAtTheThrustersLine) {
  const TempDir t;
  // The case: every thruster along +x. Nothing pushes sideways, down or turns.
  const std::string all_x = t.write(
      "all_x.yaml", "calibration: " + kCalibration +
                        "\nvehicle:\n  thrusters:\n    thrusters:\n"
                        "      - {name: a, position_m: [0.1, 0.1, 0], direction: [1, 0, 0], "
                        "channel: 0}\n"
                        "      - {name: b, position_m: [0.1, -0.1, 0], direction: [1, 0, 0], "
                        "channel: 1}\n");
  EXPECT_EQ(validation_error_of(all_x),
            all_x +
                ":4: vehicle.thrusters.thrusters: no thruster pushes along the servo's y "
                "(sway) axis: the layout cannot control it");
  // Every axis has a thruster, but x and y can only be pushed together.
  const std::string coupled =
      t.write("coupled.yaml",
              "calibration: " + kCalibration +
                  "\nvehicle:\n  thrusters:\n    thrusters:\n"
                  "      - {name: a, position_m: [0, 0, 0], direction: [0.7071, 0.7071, 0], "
                  "channel: 0}\n"
                  "      - {name: b, position_m: [0.2, 0, 0], direction: [0.7071, 0.7071, "
                  "0], channel: 1}\n"
                  "      - {name: c, position_m: [0, 0, 0], direction: [0, 0, 1], "
                  "channel: 2}\n");
  const std::string e = validation_error_of(coupled);
  EXPECT_EQ(
      e.rfind(coupled +
                  ":4: vehicle.thrusters.thrusters: the thrusters cannot push the servo's axes "
                  "(x (surge), y (sway), z (heave), yaw) independently",
              0),
      0u)
      << e;
  // A channel used twice is the allocator's check, now at the same line before any device.
  const std::string twice =
      t.write("twice.yaml",
              "calibration: " + kCalibration +
                  "\nvehicle:\n  thrusters:\n    thrusters:\n"
                  "      - {name: a, position_m: [0, 0, 0], direction: [1, 0, 0], channel: 0}\n"
                  "      - {name: b, position_m: [0, 0, 0], direction: [0, 1, 0], channel: 0}\n");
  EXPECT_EQ(validation_error_of(twice).rfind(twice + ":4: vehicle.thrusters.thrusters: ", 0), 0u)
      << validation_error_of(twice);
}

TEST(ConfigValidation, TheBusIsReportedDegradedBeforeTheWatchdogStopsIt) {
  const TempDir t;
  const std::string late = t.write(
      "late.yaml", "calibration: " + kCalibration +
                       "\nthruster_bus:\n  timing:\n    watchdog_ms: 200\n    degraded_ms: 250\n");
  EXPECT_EQ(validation_error_of(late),
            late +
                ":5: thruster_bus.timing.degraded_ms: must be below "
                "thruster_bus.timing.watchdog_ms (a slow bus is reported before "
                "the controller stops on it)");
  const std::string fine = t.write(
      "fine.yaml", "calibration: " + kCalibration +
                       "\nthruster_bus:\n  timing:\n    watchdog_ms: 300\n    degraded_ms: 250\n");
  EXPECT_EQ(validation_error_of(fine), "");
}

TEST(ConfigValidation, TheCameraExposureFitsTheFramePeriodAndATemperatureNeedsTheLock) {
  const TempDir t;
  const std::string slow =
      t.write("slow.yaml", "calibration: " + kCalibration +
                               "\ncamera:\n  v4l2:\n    fps: 30\n    auto_exposure: false\n"
                               "    exposure_time_us: 40000\n");
  EXPECT_EQ(validation_error_of(slow),
            slow +
                ":6: camera.v4l2.exposure_time_us: 40000 us does not fit in the "
                "frame period at camera.v4l2.fps 30 (33333 us)");
  // Auto exposure ignores the time: no error.
  const std::string automatic =
      t.write("auto.yaml", "calibration: " + kCalibration +
                               "\ncamera:\n  v4l2:\n    fps: 30\n    exposure_time_us: 40000\n");
  EXPECT_EQ(validation_error_of(automatic), "");
  const std::string temperature = t.write(
      "temperature.yaml", "calibration: " + kCalibration +
                              "\ncamera:\n  v4l2:\n    white_balance_temperature_k: 5000\n");
  EXPECT_EQ(validation_error_of(temperature),
            temperature +
                ":4: camera.v4l2.white_balance_temperature_k: needs camera.v4l2.white_balance "
                "lock (auto white balance ignores it)");
}

TEST(ConfigValidation, TheArdusubLinkAndAckTimeoutAreCheckedAtTheirLine) {
  const TempDir t;
  const std::string link = t.write("link.yaml", "calibration: " + kCalibration +
                                                    "\nthruster_bus:\n  backend: ardusub\n"
                                                    "  ardusub:\n    link: udp:0.0.0.0:14660\n");
  EXPECT_NE(validation_error_of(link).find(
                link + ":5: thruster_bus.ardusub.link: 'udp:0.0.0.0:14660' has an unknown mode"),
            std::string::npos)
      << validation_error_of(link);
  const std::string ack = t.write("ack.yaml", "calibration: " + kCalibration +
                                                  "\nthruster_bus:\n  backend: ardusub\n"
                                                  "  ardusub:\n    ack_timeout_ms: 800\n");
  EXPECT_EQ(validation_error_of(ack),
            ack +
                ":5: thruster_bus.ardusub.ack_timeout_ms: must be below "
                "thruster_bus.timing.close_timeout_ms (the I/O thread answers the "
                "final disarm within it)");
  const std::string fine = t.write("fine.yaml", "calibration: " + kCalibration +
                                                    "\nthruster_bus:\n  backend: ardusub\n"
                                                    "  ardusub:\n    link: udpin:0.0.0.0:14660\n");
  EXPECT_EQ(validation_error_of(fine), "");
}

TEST(ConfigValidation, TheArdusubChannelMapIsCheckedAtItsLine) {
  const TempDir t;
  const std::string f = t.write("rc.yaml", "calibration: " + kCalibration +
                                               "\nthruster_bus:\n  backend: ardusub\n"
                                               "  ardusub:\n    mode: thrusters\n"
                                               "    rc_override:\n      channels:\n"
                                               "        - {thruster: nowhere, channel: 3}\n");
  EXPECT_EQ(validation_error_of(f).rfind(
                f + ":6: thruster_bus.ardusub.rc_override.channels: 1 given for ", 0),
            0U)
      << validation_error_of(f);
  const std::string range =
      t.write("pwm.yaml", "calibration: " + kCalibration +
                              "\nthruster_bus:\n  backend: ardusub\n"
                              "  ardusub:\n    rc_override:\n      pwm_min_us: 1500\n");
  EXPECT_EQ(validation_error_of(range),
            range +
                ":5: thruster_bus.ardusub.rc_override.pwm_neutral_us: must lie "
                "between pwm_min_us and pwm_max_us");
}

TEST(ConfigValidation, ArdusubSensorsNeedTheArdusubBus) {
  const TempDir t;
  const std::string f =
      t.write("s.yaml", "calibration: " + kCalibration + "\nsensors:\n  backend: ardusub\n");
  EXPECT_EQ(validation_error_of(f),
            f + ":3: sensors.backend: ardusub needs thruster_bus.backend ardusub (its "
                "link carries them)");
}

TEST(ConfigValidation, AMarkerNeedsThreeColoursAtDistinctPlaces) {
  const TempDir t;
  auto marker = [&t](const std::string& name, const std::string& spheres) {
    return t.write(name, "calibration: " + kCalibration + "\nmarker:\n  spheres:\n" + spheres);
  };
  const std::string red3 = marker("red3.yaml",
                                  "    - {name: red, centre_m: [-0.06, 0.03, 0]}\n"
                                  "    - {name: red, centre_m: [0.06, 0.03, 0]}\n"
                                  "    - {name: red, centre_m: [0, -0.06, -0.04]}\n");
  EXPECT_EQ(validation_error_of(red3),
            red3 +
                ":5: marker.spheres[1].name: 'red' is also sphere 0's colour: the "
                "marker needs one red, one green and one blue sphere");
  const std::string coincident = marker("coincident.yaml",
                                        "    - {name: red, centre_m: [-0.06, 0.03, 0]}\n"
                                        "    - {name: green, centre_m: [-0.06, 0.03, 0]}\n"
                                        "    - {name: blue, centre_m: [0, -0.06, -0.04]}\n");
  EXPECT_EQ(validation_error_of(coincident)
                .rfind(coincident + ":5: marker.spheres[1].centre_m: the green and red "
                                    "spheres are -0.04 m apart surface to surface",
                       0),
            0u)
      << validation_error_of(coincident);
  const std::string collinear = marker("collinear.yaml",
                                       "    - {name: red, centre_m: [-0.1, 0, 0]}\n"
                                       "    - {name: green, centre_m: [0.1, 0, 0]}\n"
                                       "    - {name: blue, centre_m: [0, 0.01, 0]}\n");
  EXPECT_EQ(validation_error_of(collinear).rfind(
                collinear + ":6: marker.spheres[2].centre_m: the blue sphere "
                            "is 0.01 m from the line through the other two",
                0),
            0u)
      << validation_error_of(collinear);
  const std::string two = marker("two.yaml",
                                 "    - {name: red, centre_m: [-0.06, 0.03, 0]}\n"
                                 "    - {name: green, centre_m: [0.06, 0.03, 0]}\n");
  EXPECT_EQ(validation_error_of(two).rfind(two + ":3: marker.spheres: expected 3 spheres", 0), 0u)
      << validation_error_of(two);
}

TEST(ConfigValidation, ImplausibleCalibrationsAreRejectedAtTheirLine) {
  const TempDir t;
  auto config = [&t](const std::string& name, const std::string& calibration) {
    return t.write(name, "calibration: " + calibration + "\n");
  };
  // The two: `check` rejected them, `run` armed with them.
  const std::string cx =
      config("cx.yaml", t.calibration("cx_cal.yaml", "552.0, 0., 331.5,", "552.0, 0., -5000.,"));
  EXPECT_EQ(validation_error_of(cx),
            (t.dir / "cx_cal.yaml").string() +
                ":8: K1: principal point (-5000, 236) px lies outside the 640x480 "
                "image");
  const std::string k1 =
      config("k1.yaml", t.calibration("k1_cal.yaml", "[ -0.12, 0.05,", "[ 1000000., 0.05,"));
  EXPECT_EQ(validation_error_of(k1),
            (t.dir / "k1_cal.yaml").string() +
                ":13: D1: k1 = 1e+06 is beyond validation.max_abs_k1 (|k1| <= 2)");
  const std::string baseline =
      config("baseline.yaml",
             t.calibration("baseline_cal.yaml", "[ -0.1775664009462487, 0.,", "[ -2.5, 0.,"));
  EXPECT_EQ(validation_error_of(baseline).rfind(
                (t.dir / "baseline_cal.yaml").string() + ":33: T: baseline 2.5", 0),
            0u)
      << validation_error_of(baseline);
  const std::string focal = config(
      "focal.yaml",
      t.calibration("focal_cal.yaml", "552.0, 0., 331.5, 0., 549.0", "5.0, 0., 331.5, 0., 549.0"));
  EXPECT_EQ(validation_error_of(focal).rfind((t.dir / "focal_cal.yaml").string() + ":8: K1: ", 0),
            0u)
      << validation_error_of(focal);
  // A limit widened in the config is what the check uses.
  const std::string k1_50 = t.calibration("k1_50_cal.yaml", "[ -0.12, 0.05,", "[ 50., 0.05,");
  EXPECT_NE(validation_error_of(config("k1_50.yaml", k1_50)), "");
  const std::string widened =
      t.write("widened.yaml", "calibration: " + k1_50 + "\nvalidation:\n  max_abs_k1: 60\n");
  EXPECT_EQ(validation_error_of(widened), "");
}

TEST(ConfigValidation, ACalibrationKeyGivenTwiceIsAnError) {
  const TempDir t;
  const std::string cal = t.calibration("twice_cal.yaml", "image_size: [ 640, 480 ]\n",
                                        "image_size: [ 640, 480 ]\nimage_size: [ 320, 240 ]\n");
  const std::string config = t.write("twice.yaml", "calibration: " + cal + "\n");
  EXPECT_EQ(validation_error_of(config),
            cal + ":8: key 'image_size' given twice (the first is line 7)");
}

TEST(ConfigValidation, NoContactSensorMeansVisionContactWithAWarning) {
  const TempDir t;
  const std::string hardware =
      t.write("hardware.yaml", "calibration: " + kCalibration +
                                   "\ncamera:\n  backend: v4l2\nthruster_bus:\n  backend: modbus\n"
                                   "mission:\n  contact_switch: true\n");
  const AppConfig c = load_app_config(hardware);
  EXPECT_FALSE(c.mission.contact_switch);
  EXPECT_TRUE(c.mission.contact_from_vision) << "DOCK must be able to end";
  ASSERT_EQ(c.warnings.size(), 1u);
  EXPECT_EQ(c.warnings[0].rfind(hardware + ":7: mission.contact_switch: no backend reports a dock "
                                           "contact (camera.backend v4l2, thruster_bus.backend "
                                           "modbus",
                                0),
            0u)
      << c.warnings[0];
  // The mock HAL reports the contact: nothing to adjust.
  const AppConfig sim = load_app_config(t.write("sim.yaml", "calibration: " + kCalibration + "\n"));
  EXPECT_TRUE(sim.mission.contact_switch);
  EXPECT_TRUE(sim.warnings.empty());
  const std::string neither = t.write(
      "neither.yaml", "calibration: " + kCalibration +
                          "\nmission:\n  contact_switch: false\n  contact_from_vision: false\n");
  EXPECT_EQ(
      validation_error_of(neither).rfind(neither + ":4: mission.contact_from_vision: neither", 0),
      0u)
      << validation_error_of(neither);
}

TEST(ConfigValidation, LocationsFallBackToTheNearestGivenKey) {
  const TempDir t;
  const std::string file = t.write(
      "lines.yaml", "calibration: " + kCalibration + "\nvehicle:\n  thrusters:\n    thrusters:\n" +
                        "      - {name: a, position_m: [0, 0, 0], direction: [1, 0, 0], "
                        "channel: 0}\n");
  AppConfig c;
  try {
    c = load_app_config(file);
  } catch (const ConfigError&) {
    // the one-thruster layout is rejected; the lines are what this test reads
  }
  c.config_file = file;
  load_yaml_file(
      file, [&c](hal::ParamVisitor& v) { describe(v, c); }, &c.key_lines);
  EXPECT_EQ(config_location(c, "vehicle.thrusters.thrusters[0].direction"),
            file + ":5: vehicle.thrusters.thrusters[0].direction");
  EXPECT_EQ(config_location(c, "vehicle.thrusters.thrusters[0].max_forward_n"),
            file + ":5: vehicle.thrusters.thrusters[0].max_forward_n");
  EXPECT_EQ(config_location(c, "vehicle.thrusters.thrusters"),
            file + ":4: vehicle.thrusters.thrusters");
  EXPECT_EQ(config_location(c, "vehicle.probe_tip_m"), file + ":2: vehicle.probe_tip_m");
  EXPECT_EQ(config_location(c, "mission.kind"), file + ": mission.kind");
}

}  // namespace
}  // namespace rovctl::app
