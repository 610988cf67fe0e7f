// Settings of the Modbus thruster bus (RTU over RS-485 or TCP); see deploy/modbus-register-map.md.
#pragma once

#include <string>

#include "hal/primitives/parameters.hpp"

namespace rovctl::drivers {

struct ModbusParams {
  std::string transport = "rtu";  // "rtu" (serial, RS-485) or "tcp"
  std::string host = "127.0.0.1";
  int port = 502;
  std::string serial_device = "/dev/ttyUSB0";
  int baud = 115200;
  std::string parity = "none";  // none | even | odd
  int data_bits = 8;
  int stop_bits = 1;
  bool rs485 = false;  // switch the UART into kernel RS-485 mode (RTS drives the transceiver)
  int slave_id = 1;
  int response_timeout_ms = 20;  // an answer later than this is counted late
  int late_answer_ms = 30;       // how much longer a late answer is still awaited and taken
  int retries = 1;  // extra attempts of an unanswered heartbeat, read or neutral (never of thrust)
  int max_consecutive_failures = 3;  // failed ticks in a row before write() reports a fault
};

void describe(hal::ParamVisitor& v, ModbusParams& p);

}  // namespace rovctl::drivers
