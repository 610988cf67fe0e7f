// Decoding of the battery and charger registers: fixed-point to SI, validity from the status word.
#include "drivers/modbus/modbus_battery_registers.hpp"

namespace rovctl::drivers {

void decode_battery_registers(const std::array<std::uint16_t, modbus_map::kBatteryRegisterCount>& r,
                              hal::SensorReadings& readings) {
  const std::uint16_t status = r[3];
  readings.charger_valid = (status & 0x1u) != 0;
  readings.charge_current_a =
      readings.charger_valid ? 0.01 * static_cast<double>(static_cast<std::int16_t>(r[0])) : 0.0;
  readings.battery_valid = (status & 0x2u) != 0;
  readings.soc_fraction = readings.battery_valid ? 0.001 * static_cast<double>(r[1]) : 0.0;
  readings.battery_voltage_v = readings.battery_valid ? 0.01 * static_cast<double>(r[2]) : 0.0;
}

}  // namespace rovctl::drivers
