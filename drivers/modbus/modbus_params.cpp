// Parameter declarations of the Modbus thruster bus.
#include "drivers/modbus/modbus_params.hpp"

namespace rovctl::drivers {

void describe(hal::ParamVisitor& v, ModbusParams& p) {
  v.param("transport", p.transport, "rtu: serial line (RS-485); tcp: Modbus TCP", {"rtu", "tcp"});
  v.param("host", p.host, "Modbus TCP server address (transport tcp)");
  v.param("port", p.port, {"-", 1, 65535, "Modbus TCP port (transport tcp)"});
  v.param("serial_device", p.serial_device, "serial device of the RS-485 line (transport rtu)");
  v.param("baud", p.baud, {"bit/s", 1200, 4000000, "serial line speed (transport rtu)"});
  v.param("parity", p.parity, "serial parity (transport rtu)", {"none", "even", "odd"});
  v.param("data_bits", p.data_bits, {"-", 7, 8, "serial data bits (transport rtu)"});
  v.param("stop_bits", p.stop_bits, {"-", 1, 2, "serial stop bits (transport rtu)"});
  v.param("rs485", p.rs485,
          "put the UART in kernel RS-485 mode (for adapters whose RTS drives the transceiver)");
  v.param("slave_id", p.slave_id, {"-", 1, 247, "Modbus unit id of the thruster controller"});
  v.param("response_timeout_ms", p.response_timeout_ms,
          {"ms", 1, 1000,
           "time within which the controller should answer one request; a later answer is "
           "counted late (a controller out of its timing), not failed"});
  v.param("late_answer_ms", p.late_answer_ms,
          {"ms", 0, 1000,
           "how much longer than response_timeout_ms an answer is still awaited and taken: a "
           "slow controller executes the request anyway, and an answer left to arrive during "
           "the next request would make that one fail too"});
  v.param("retries", p.retries,
          {"-", 0, 5,
           "extra attempts of an unanswered heartbeat, telemetry read, neutral or disarm; a "
           "thrust command is never sent twice (a silent controller may be hung, and would "
           "execute the copy late when it resumes)"});
  v.param("max_consecutive_failures", p.max_consecutive_failures,
          {"-", 1, 100, "failed ticks in a row after which the bus reports a fault (failsafe)"});
}

}  // namespace rovctl::drivers
