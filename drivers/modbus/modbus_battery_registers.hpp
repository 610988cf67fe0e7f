// The battery and charger input registers of rovctl's Modbus map (deploy/modbus-register-map.md):
// the station charger's current sense and the battery monitor, decoded into hal::SensorReadings.
#pragma once

#include <array>
#include <cstdint>

#include "hal/interfaces/sensors.hpp"

namespace rovctl::drivers {

namespace modbus_map {
constexpr int kChargeCurrentRegister = 16;   // input 16: int16, charge current in 10 mA
constexpr int kStateOfChargeRegister = 17;   // input 17: uint16, state of charge in permille
constexpr int kBatteryVoltageRegister = 18;  // input 18: uint16, battery voltage in 10 mV
constexpr int kChargerStatusRegister = 19;   // input 19: bit 0 charger valid, bit 1 battery valid
constexpr int kBatteryRegisterCount = 4;
}  // namespace modbus_map

// Input registers 16-19 as read; a status bit clear leaves that half invalid (its value 0).
void decode_battery_registers(
    const std::array<std::uint16_t, modbus_map::kBatteryRegisterCount>& registers,
    hal::SensorReadings& readings);

}  // namespace rovctl::drivers
