#!/bin/sh
# CAN bring-up for DroneCAN thrusters: can-up.sh IFACE BITRATE (restarts after bus-off in 100 ms).
set -eu
iface=${1:-can0}
bitrate=${2:-1000000}
ip link set "$iface" down 2>/dev/null || true
ip link set "$iface" type can bitrate "$bitrate" restart-ms 100
ip link set "$iface" txqueuelen 128
ip link set "$iface" up
ip -details link show "$iface"
