// The strict YAML loader: every kind of bad input names the file, line and key.
#include "app/runtime/config_loader.hpp"

#include <gtest/gtest.h>
#include <unistd.h>

#include <cstdio>
#include <fstream>
#include <string>

#include "app/runtime/app_config.hpp"
#include "app/runtime/errors.hpp"

namespace rovctl::app {
namespace {

AppConfig load(const std::string& text) {
  AppConfig config;
  load_yaml_text(text, "test.yaml", "/base",
                 [&config](hal::ParamVisitor& v) { describe(v, config); });
  return config;
}

std::string error_of(const std::string& text) {
  try {
    load(text);
  } catch (const ConfigError& e) {
    return e.what();
  }
  return "";
}

TEST(ConfigLoader, LoadsValuesAndResolvesPaths) {
  const AppConfig c = load(
      "calibration: cal.yaml\n"
      "marker:\n"
      "  spheres:\n"
      "    - {name: green, centre_m: [0.1, 0.0, 0.0], radius_m: 0.03}\n");
  EXPECT_EQ(c.calibration_file, "/base/cal.yaml");
  ASSERT_EQ(c.marker.spheres.size(), 1u);
  EXPECT_EQ(c.marker.spheres[0].colour, hal::ColourClass::green);
  EXPECT_DOUBLE_EQ(c.marker.spheres[0].radius_m, 0.03);
  // Unspecified fields come from the standard sphere of that colour, not another colour's.
  EXPECT_DOUBLE_EQ(c.marker.spheres[0].hue_min_deg, 85.0);
}

TEST(ConfigLoader, UnknownKeyNamesPathAndLine) {
  EXPECT_EQ(error_of("calibration: c.yaml\nmarker:\n  sphere: []\n"),
            "test.yaml:3: marker.sphere: unknown key");
}

TEST(ConfigLoader, DuplicateKeysAndSectionsAreErrors) {
  EXPECT_EQ(error_of("calibration: a.yaml\ncalibration: b.yaml\n"),
            "test.yaml:2: calibration: given twice (the first is line 1)");
  EXPECT_EQ(error_of("calibration: c.yaml\nestimator:\n  mode: faithful\n"
                     "estimator:\n  mode: improved\n"),
            "test.yaml:4: estimator: given twice (the first is line 2)");
  EXPECT_EQ(error_of("calibration: c.yaml\nestimator:\n  mode: faithful\n  mode: improved\n"),
            "test.yaml:4: estimator.mode: given twice (the first is line 3)");
}

TEST(ConfigLoader, MissingRequiredKey) {
  EXPECT_EQ(error_of("marker: {}\n"), "test.yaml:1: calibration: missing required key");
}

TEST(ConfigLoader, WrongTypeAndRange) {
  EXPECT_EQ(error_of("calibration: c.yaml\nmarker:\n  spheres:\n    - {name: red, centre_m: [0, 0, "
                     "0], radius_m: big}\n"),
            "test.yaml:4: marker.spheres[0].radius_m: expected a number, got 'big'");
  EXPECT_EQ(error_of("calibration: c.yaml\nmarker:\n  spheres:\n    - {name: red, centre_m: [0, 0, "
                     "0], radius_m: 7}\n"),
            "test.yaml:4: marker.spheres[0].radius_m: 7 is out of range [0.002, 0.5] m");
  EXPECT_NE(
      error_of("calibration: c.yaml\nmarker:\n  spheres:\n    - {name: pink, centre_m: [0, 0, "
               "0]}\n")
          .find("'pink' is not one of: red, green, blue"),
      std::string::npos);
}

TEST(ConfigLoader, SyntaxErrorNamesLine) {
  EXPECT_NE(error_of("calibration: c.yaml\nmarker: [\n").find("test.yaml:"), std::string::npos);
}

TEST(ConfigLoader, CrossFieldErrorsNameTheFile) {
  // Each key is in range; together they are not (an empty search volume).
  const std::string path =
      ::testing::TempDir() + "rovctl_cross_field_" + std::to_string(::getpid()) + ".yaml";
  {
    std::ofstream f(path);
    f << "calibration: c.yaml\nestimator:\n  search:\n    x_min_m: 0.5\n    x_max_m: 0.1\n";
  }
  try {
    load_app_config(path);
    ADD_FAILURE() << "an empty search volume was accepted";
  } catch (const ConfigError& e) {
    const std::string what = e.what();
    EXPECT_NE(what.find(path), std::string::npos) << what;
    EXPECT_NE(what.find("x"), std::string::npos) << what;
  }
  std::remove(path.c_str());
}

TEST(ConfigLoader, DocumentsEveryParameter) {
  AppConfig c;
  const std::string doc =
      describe_parameters_markdown([&c](hal::ParamVisitor& v) { describe(v, c); });
  EXPECT_NE(doc.find("`marker.spheres[].radius_m` | number | m | 0.002 .. 0.5 | 0.02"),
            std::string::npos);
}

}  // namespace
}  // namespace rovctl::app
