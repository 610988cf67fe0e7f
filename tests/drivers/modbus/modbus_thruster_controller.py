#!/usr/bin/python3
"""A stand-in thruster controller for the Modbus bus tests, built on pymodbus (3.0.0rc1).

Serves rovctl's register map (deploy/modbus-register-map.md) on TCP or RTU and appends every
write to a holding register to --log as one line: "<monotonic s> hr <address> <v0> <v1> ...".
Input registers answer with rpm = 3 * commanded permille and fault flags = 0x100 + channel. Like
the real controller it zeroes the commands when the heartbeat (register 16) stalls for 200 ms
while a command is non-zero, and logs "<t> watchdog_stop". --ready-file receives "port <n>" once it serves.
--delay-ms makes every answer that late (a slow controller or a congested line; a large value is
a hung one).
"""
import argparse
import asyncio
import os
import sys
import time

from pymodbus.datastore import (ModbusSequentialDataBlock, ModbusServerContext,
                                ModbusSlaveContext)
from pymodbus.server.async_io import ModbusSerialServer, ModbusTcpServer
from pymodbus.transaction import ModbusRtuFramer, ModbusSocketFramer

CHANNELS = 8
HEARTBEAT = 16
ARMED = 17
WATCHDOG_S = 0.200


class Controller:
    def __init__(self, log):
        self.log = log
        self.inputs = ModbusSequentialDataBlock(0, [0] * 16)
        for ch in range(CHANNELS):
            self.inputs.setValues(CHANNELS + ch, [0x100 + ch])
        self.last_heartbeat_s = time.monotonic()
        self.holding = Holding(self)

    def record(self, address, values):
        self.log.write("%.6f hr %d %s\n" % (time.monotonic(), address,
                                            " ".join(str(v) for v in values)))
        self.log.flush()
        for i, v in enumerate(values):
            reg = address + i
            if reg < CHANNELS:
                permille = v - 65536 if v >= 32768 else v
                self.inputs.setValues(reg, [(3 * permille) & 0xFFFF])
            elif reg == HEARTBEAT:
                self.last_heartbeat_s = time.monotonic()

    async def watchdog(self):
        while True:
            await asyncio.sleep(0.02)
            commands = self.holding.getValues(0, CHANNELS)
            stalled = time.monotonic() - self.last_heartbeat_s > WATCHDOG_S
            if stalled and any(commands):
                ModbusSequentialDataBlock.setValues(self.holding, 0, [0] * CHANNELS)
                self.log.write("%.6f watchdog_stop\n" % time.monotonic())
                self.log.flush()


class SlowSlaveContext(ModbusSlaveContext):
    """Delays every request once: pymodbus validates each request exactly once before executing
    it, so the delay is per answer (FC06 reads its register back after writing: not twice)."""

    def __init__(self, delay_s, **kwargs):
        super().__init__(**kwargs)
        self.delay_s = delay_s

    def validate(self, fc_as_hex, address, count=1):
        if self.delay_s > 0:
            # The server answers one request at a time, as the real controller's UART task does.
            time.sleep(self.delay_s)
        return super().validate(fc_as_hex, address, count)


class Holding(ModbusSequentialDataBlock):
    def __init__(self, controller):
        super().__init__(0, [0] * 32)
        self.controller = controller

    def setValues(self, address, values):  # pylint: disable=invalid-name
        if not isinstance(values, list):
            values = [values]
        super().setValues(address, values)
        self.controller.record(address, values)


def write_ready(path, port):
    tmp = path + ".tmp"
    with open(tmp, "w", encoding="ascii") as f:
        f.write("port %d\n" % port)
    os.rename(tmp, path)


async def main():
    ap = argparse.ArgumentParser()
    ap.add_argument("--transport", choices=["tcp", "rtu"], required=True)
    ap.add_argument("--device", help="serial device (rtu)")
    ap.add_argument("--baud", type=int, default=115200)
    ap.add_argument("--slave-id", type=int, default=1)
    ap.add_argument("--log", required=True)
    ap.add_argument("--ready-file", required=True)
    ap.add_argument("--delay-ms", type=float, default=0.0, help="answer every request this late")
    args = ap.parse_args()

    log = open(args.log, "w", encoding="ascii")  # pylint: disable=consider-using-with
    controller = Controller(log)
    slave = SlowSlaveContext(args.delay_ms / 1000.0, hr=controller.holding, ir=controller.inputs,
                             zero_mode=True)
    # Only our unit id exists; requests to any other are not answered (a silent slave).
    context = ModbusServerContext(slaves={args.slave_id: slave}, single=False)
    asyncio.get_running_loop().create_task(controller.watchdog())
    if args.transport == "tcp":
        # pymodbus 3.0.0rc1's StartAsyncTcpServer drops its address argument: build the server.
        server = ModbusTcpServer(context, framer=ModbusSocketFramer, address=("127.0.0.1", 0),
                                 ignore_missing_slaves=True)
        task = asyncio.get_running_loop().create_task(server.serve_forever())
        await server.serving
        write_ready(args.ready_file, server.server.sockets[0].getsockname()[1])
        await task
    else:
        # StartAsyncSerialServer defaults to the ASCII framer in this version: build the server.
        server = ModbusSerialServer(context, framer=ModbusRtuFramer, port=args.device,
                                    baudrate=args.baud, ignore_missing_slaves=True)
        await server.start()
        write_ready(args.ready_file, 0)
        await server.serve_forever()


if __name__ == "__main__":
    try:
        asyncio.run(main())
    except KeyboardInterrupt:
        sys.exit(0)
