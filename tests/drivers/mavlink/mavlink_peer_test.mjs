// An independent MAVLink peer: node-mavlink (npm) against rovctl's codec over loopback UDP.
// rovctl's side (mavlink_peer_exchange) listens on udpin; this peer sends each message
// rovctl speaks with known values (plus a broken CRC, a signed frame and leading garbage, which
// rovctl must refuse), rovctl checks them, then sends the same messages back from 255/190 and
// this peer checks ids, lengths, truncation, CRCs, sys/comp ids, sequence and values.
// Usage: node mavlink_peer_test.mjs MAVLINK_PEER_EXCHANGE   (exit 77: skipped)
import { spawn } from "node:child_process";
import dgram from "node:dgram";
import readline from "node:readline";

const [exchange] = process.argv.slice(2);

function skip(why) { console.log("SKIP: " + why); process.exit(77); }
function fail(why) { console.error("FAIL: " + why); process.exit(1); }
function check(cond, what) { if (!cond) fail(what); console.log("ok: " + what); }
let failures = 0;
function expect(cond, what) { if (!cond) { console.error("FAIL: " + what); failures++; } }

let mavlink;
try { mavlink = await import("node-mavlink"); }
catch { skip("node-mavlink not installed (npm ci --prefix tests)"); }
const { MavLinkProtocolV2, minimal, common, x25crc } = mavlink;
const REGISTRY = { ...minimal.REGISTRY, ...common.REGISTRY };

// The same values as exchanged_messages() in mavlink_peer_exchange.cpp, in the same order.
// `fields` are node-mavlink's names as decoded; `make` builds the message to send.
const plain = (clazz, fields) => ({ clazz, fields, make: () => Object.assign(new clazz(), fields) });
const MESSAGES = [
  plain(minimal.Heartbeat, { customMode: 19, type: 12, autopilot: 3, baseMode: 0xc1,
                             systemStatus: 4, mavlinkVersion: 3 }),
  plain(common.SysStatus, {
    onboardControlSensorsPresent: 0x0001ffff, onboardControlSensorsEnabled: 0x0000ff0f,
    onboardControlSensorsHealth: 0x0000f00f, load: 250, voltageBattery: 15800,
    currentBattery: -1234, dropRateComm: 0, errorsComm: 0, errorsCount1: 1, errorsCount2: 2,
    errorsCount3: 3, errorsCount4: 4, batteryRemaining: 76,
    onboardControlSensorsPresentExtended: 0, onboardControlSensorsEnabledExtended: 0,
    onboardControlSensorsHealthExtended: 0 }),
  plain(common.ParamRequestRead, { paramIndex: -1, targetSystem: 1, targetComponent: 1,
                                   paramId: "FS_PILOT_INPUT" }),
  plain(common.ParamValue, { paramValue: 3, paramCount: 873, paramIndex: 412,
                             paramId: "FS_PILOT_TIMEOUT", paramType: 9 }),
  plain(common.AttitudeQuaternion, { timeBootMs: 123456, q1: 0.5, q2: -0.5, q3: 0.5, q4: 0.5,
                                     rollspeed: 0.125, pitchspeed: -0.25, yawspeed: 1.5,
                                     reprOffsetQ: [0, 0, 0, 0] }),
  plain(common.ManualControl, { x: -1000, y: 1000, z: 500, r: -250, buttons: 0, target: 1,
                                buttons2: 0, enabledExtensions: 0, s: 0, t: 0, aux1: 0, aux2: 0,
                                aux3: 0, aux4: 0, aux5: 0, aux6: 0 }),
  plain(common.RcChannelsOverride, {
    chan1Raw: 1100, chan2Raw: 1200, chan3Raw: 1300, chan4Raw: 1400, chan5Raw: 1500,
    chan6Raw: 1600, chan7Raw: 1700, chan8Raw: 1800, targetSystem: 1, targetComponent: 1,
    chan9Raw: 1500, chan10Raw: 65535, chan11Raw: 0, chan12Raw: 0, chan13Raw: 0, chan14Raw: 0,
    chan15Raw: 0, chan16Raw: 0, chan17Raw: 0, chan18Raw: 0 }),
  plain(common.VfrHud, { airspeed: 0.25, groundspeed: 0.5, alt: -12.75, climb: -0.125,
                         heading: 271, throttle: 40 }),
  { clazz: common.CommandLong,  // MAV_CMD_COMPONENT_ARM_DISARM, built with the typed class
    fields: { command: 400, targetSystem: 1, targetComponent: 1, confirmation: 0, _param1: 1,
              _param2: 0, _param3: 0, _param4: 0, _param5: 0, _param6: 0, _param7: 0 },
    make: () => { const c = new common.ComponentArmDisarmCommand(1, 1); c.arm = 1; c.force = 0;
                  return c; } },
  { clazz: common.CommandLong,  // MAV_CMD_SET_MESSAGE_INTERVAL for ATTITUDE_QUATERNION at 30 Hz
    fields: { command: 511, targetSystem: 1, targetComponent: 1, confirmation: 0, _param1: 31,
              _param2: 33333, _param3: 0, _param4: 0, _param5: 0, _param6: 0, _param7: 0 },
    make: () => { const c = new common.SetMessageIntervalCommand(1, 1); c.messageId = 31;
                  c.interval = 33333; return c; } },
  plain(common.CommandAck, { command: 400, result: 0, progress: 0, resultParam2: 0,
                             targetSystem: 255, targetComponent: 190 }),
  plain(common.ScaledPressure2, { timeBootMs: 123456, pressAbs: 2013.25, pressDiff: 0,
                                  temperature: 1234, temperaturePressDiff: 0 }),
  plain(common.NamedValueFloat, { timeBootMs: 654321, value: -0.375, name: "lat_err_m" }),
  plain(common.StatusText, { severity: 2, text: "Leak Detected", id: 0, chunkSeq: 0 }),
];
const END = () => Object.assign(new common.StatusText(), { severity: 6, text: "END" });

function same(a, b) {
  if (Array.isArray(b)) return Array.isArray(a) && a.length === b.length && a.every((v, i) => v === b[i]);
  return a === b;
}

const child = spawn(exchange, [], { stdio: ["ignore", "pipe", "inherit"] });
const childExit = new Promise((resolve) => child.on("exit", (code) => resolve(code)));
const lines = [];
let onLine = null;
readline.createInterface({ input: child.stdout }).on("line", (line) => {
  console.log("rovctl: " + line);
  lines.push(line);
  if (onLine) onLine(line);
});
const port = await new Promise((resolve, reject) => {
  const timer = setTimeout(() => reject(new Error("rovctl printed no PORT")), 10000);
  onLine = (line) => { const m = /^PORT (\d+)$/.exec(line); if (m) { clearTimeout(timer); resolve(+m[1]); } };
  child.on("exit", (code) => reject(new Error(`exchange exited ${code} before PORT`)));
}).catch((e) => fail(e.message));

// rovctl's message table against node-mavlink's generated definitions.
for (const line of lines.filter((l) => l.startsWith("TABLE "))) {
  const [, name, id, min, max, crc] = line.split(" ");
  const clazz = REGISTRY[+id];
  expect(clazz && clazz.MSG_NAME === name, `table: ${name} is id ${id} in node-mavlink`);
  if (!clazz) continue;
  const base = clazz.FIELDS.filter((f) => !f.extension)
    .reduce((n, f) => n + (f.length === 0 ? f.size : f.length * f.size), 0);
  expect(+min === base, `table: ${name} min length ${min} (node-mavlink ${base})`);
  expect(+max === clazz.PAYLOAD_LENGTH, `table: ${name} max length ${max} (node-mavlink ${clazz.PAYLOAD_LENGTH})`);
  expect(+crc === clazz.MAGIC_NUMBER, `table: ${name} CRC_EXTRA ${crc} (node-mavlink ${clazz.MAGIC_NUMBER})`);
}
check(lines.filter((l) => l.startsWith("TABLE ")).length === 13 && failures === 0,
      "rovctl's table of 13 messages agrees with node-mavlink (ids, lengths, CRC_EXTRA)");

// Receive rovctl's frames: one frame per datagram, checked on its own.
const socket = dgram.createSocket("udp4");
const received = [];
let gotEnd;
const ended = new Promise((resolve) => { gotEnd = resolve; });
const protocol = new MavLinkProtocolV2(1, 1);
socket.on("message", (buf) => {
  received.push(buf);
  if (buf.length > 12 && buf.readUIntLE(7, 3) === common.StatusText.MSG_ID &&
      protocol.data(protocol.payload(buf), common.StatusText).text === "END") gotEnd();
});
await new Promise((resolve) => socket.bind(0, "127.0.0.1", resolve));
const sendTo = (buf) => new Promise((resolve, reject) =>
  socket.send(buf, port, "127.0.0.1", (err) => (err ? reject(err) : resolve())));

// node-mavlink -> rovctl, from system 1 component 1 (ArduSub's ids).
let seq = 0;
const serialize = (msg) => protocol.serialize(msg, seq++ & 0xff);
// Refused by rovctl, sent with the sequence number of the frame after them: a heartbeat with a
// flipped CRC byte, and a correctly signed heartbeat (rovctl does not do signing).
const broken = protocol.serialize(MESSAGES[0].make(), seq);
broken[broken.length - 1] ^= 0x5a;
await sendTo(broken);
const signer = new MavLinkProtocolV2(1, 1, MavLinkProtocolV2.IFLAG_SIGNED);
const signedFrame = signer.sign(signer.serialize(MESSAGES[0].make(), seq), 0,
                                Buffer.alloc(32, 7));
check(signedFrame[2] === 1 && signedFrame.length === 12 + signedFrame[1] + 13,
      "node-mavlink built a signed frame (incompat flag 1, 13-byte signature)");
await sendTo(signedFrame);
for (const [i, m] of MESSAGES.entries()) {
  let frame = serialize(m.make());
  if (i === 0) frame = Buffer.concat([Buffer.from([0x00, 0x55, 0xfe, 0x13]), frame]);  // garbage first
  await sendTo(frame);
}
await sendTo(serialize(END()));

const code = await Promise.race([childExit, new Promise((r) => setTimeout(() => r("timeout"), 30000))]);
if (code === "timeout") { child.kill("SIGTERM"); fail("rovctl's exchange did not finish in 30 s"); }
// Both directions are judged even when the first fails, so one run shows every fault.
const rovctlOk = code === 0 && lines.includes("RESULT ok");
console.log(`${rovctlOk ? "ok" : "FAIL"}: rovctl decoded all ${MESSAGES.length} node-mavlink messages with their values and refused the broken, signed and garbage bytes (exit ${code})`);
await Promise.race([ended, new Promise((r) => setTimeout(r, 2000))]);

// rovctl -> node-mavlink.
check(received.length === MESSAGES.length + 1, `received ${received.length} datagrams from rovctl (${MESSAGES.length} messages + END)`);
for (const [i, m] of MESSAGES.entries()) {
  const buf = received[i];
  const clazz = m.clazz;
  const name = `${clazz.MSG_NAME} #${i}`;
  const len = buf[1];
  expect(buf[0] === 0xfd, `${name}: start byte 0xFD`);
  expect(buf.length === 12 + len, `${name}: datagram is exactly one frame (${buf.length} = 12 + ${len})`);
  expect(buf[2] === 0 && buf[3] === 0, `${name}: no incompat/compat flags`);
  expect(buf[4] === i, `${name}: sequence ${buf[4]}, expected ${i}`);
  expect(buf[5] === 255 && buf[6] === 190, `${name}: from 255/190, got ${buf[5]}/${buf[6]}`);
  expect(buf.readUIntLE(7, 3) === clazz.MSG_ID, `${name}: message id ${buf.readUIntLE(7, 3)}`);
  expect(len >= 1 && len <= clazz.PAYLOAD_LENGTH, `${name}: length ${len} within 1..${clazz.PAYLOAD_LENGTH}`);
  expect(len === 1 || buf[10 + len - 1] !== 0, `${name}: trailing zeros cut (length ${len})`);
  const crc = x25crc(buf, 1, 2, clazz.MAGIC_NUMBER);
  expect(crc === buf.readUInt16LE(10 + len), `${name}: CRC ${buf.readUInt16LE(10 + len).toString(16)} (node-mavlink ${crc.toString(16)})`);
  const decoded = protocol.data(protocol.payload(buf), clazz);
  for (const [k, v] of Object.entries(m.fields)) {
    expect(same(decoded[k], v), `${name}: ${k} = ${JSON.stringify(decoded[k])}, expected ${JSON.stringify(v)}`);
  }
}
check(failures === 0 && rovctlOk, `node-mavlink decoded all ${MESSAGES.length} rovctl messages: ids, lengths, truncation, CRCs, 255/190, sequence 0..${MESSAGES.length - 1}, values`);
socket.close();
process.exit(0);
