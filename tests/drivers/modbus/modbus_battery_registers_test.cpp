// The battery and charger input registers decode to SI units, and a clear status bit is invalid.
#include "drivers/modbus/modbus_battery_registers.hpp"

#include <gtest/gtest.h>

namespace rovctl::drivers {
namespace {

TEST(ModbusBatteryRegisters, DecodesCurrentStateOfChargeAndVoltage) {
  hal::SensorReadings r;
  decode_battery_registers({1234, 875, 1642, 0x3}, r);
  EXPECT_TRUE(r.charger_valid);
  EXPECT_DOUBLE_EQ(r.charge_current_a, 12.34);
  EXPECT_TRUE(r.battery_valid);
  EXPECT_DOUBLE_EQ(r.soc_fraction, 0.875);
  EXPECT_DOUBLE_EQ(r.battery_voltage_v, 16.42);
  // A negative current (the battery feeding the charger's sense backwards) keeps its sign.
  decode_battery_registers({static_cast<std::uint16_t>(-50), 875, 1642, 0x1}, r);
  EXPECT_DOUBLE_EQ(r.charge_current_a, -0.5);
  EXPECT_FALSE(r.battery_valid);
  EXPECT_DOUBLE_EQ(r.soc_fraction, 0.0);
}

TEST(ModbusBatteryRegisters, NoStatusBitsMeansNothingValid) {
  hal::SensorReadings r;
  decode_battery_registers({1234, 875, 1642, 0x0}, r);
  EXPECT_FALSE(r.charger_valid);
  EXPECT_FALSE(r.battery_valid);
  EXPECT_DOUBLE_EQ(r.charge_current_a, 0.0);
}

}  // namespace
}  // namespace rovctl::drivers
