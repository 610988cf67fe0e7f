// A fake ArduSub written with node-mavlink (npm), independent of rovctl's codec: it beats as
// system 1 component 1, acknowledges ARM_DISARM, streams what SET_MESSAGE_INTERVAL asks for,
// answers PARAM_REQUEST_READ, and checks every datagram rovctl sends (one frame per datagram):
// control from 255/190 (the GCS id ArduSub obeys), status to the ground station from 1/191.
import dgram from "node:dgram";

export async function loadMavlink() {
  try {
    return await import("node-mavlink");
  } catch {
    return null;
  }
}

const MAV_CMD_DO_SET_MODE = 176;
const MAV_CMD_COMPONENT_ARM_DISARM = 400;
const MAV_CMD_RUN_PREARM_CHECKS = 401;
const MAV_CMD_SET_MESSAGE_INTERVAL = 511;
const ARMED_FLAG = 0x80;          // MAV_MODE_FLAG_SAFETY_ARMED
const CUSTOM_MODE_ENABLED = 0x01;  // MAV_MODE_FLAG_CUSTOM_MODE_ENABLED

export class FakeArduSub {
  // params: { NAME: value } answered to PARAM_REQUEST_READ; customMode: the mode it reports
  // (ArduSub boots in MANUAL, 19), changed by DO_SET_MODE; preArm: a reason it refuses to arm,
  // said first as ArduSub does (STATUSTEXT "PreArm: ...", then COMMAND_ACK FAILED).
  constructor(mavlink, { params = {}, customMode = 0, preArm = null } = {}) {
    this.m = mavlink;
    this.registry = { ...mavlink.minimal.REGISTRY, ...mavlink.common.REGISTRY };
    this.protocol = new mavlink.MavLinkProtocolV2(1, 1);
    this.params = params;
    this.customMode = customMode;
    this.preArm = preArm;
    this.armed = false;
    this.beating = true;
    this.seq = 0;
    this.errors = [];        // every malformed or unexpected datagram, with why
    this.log = [];           // { t_ms, id, msg } of every valid message from rovctl
    this.lastSeq = new Map();  // "sys/comp" -> last sequence number: each sender counts its own
    this.intervals = new Map();  // message id -> timer
    this.peer = null;        // rovctl's address, learnt from its first datagram
    this.listeners = [];
  }

  now() { return Number(process.hrtime.bigint()) / 1e6; }

  async start() {
    this.socket = dgram.createSocket("udp4");
    this.socket.on("message", (buf, rinfo) => this.onDatagram(buf, rinfo));
    await new Promise((resolve) => this.socket.bind(0, "127.0.0.1", resolve));
    this.port = this.socket.address().port;
    this.beatTimer = setInterval(() => { if (this.beating) this.sendHeartbeat(); }, 1000);
    return this.port;
  }

  // Every stream and the HEARTBEAT stop at once, as an ArduSub gone silent; returns when.
  silence() {
    this.beating = false;
    for (const t of this.intervals.values()) clearInterval(t);
    this.intervals.clear();
    return this.now();
  }

  stop() {
    clearInterval(this.beatTimer);
    for (const t of this.intervals.values()) clearInterval(t);
    this.intervals.clear();
    this.socket.close();
  }

  // Resolves with the first logged message for which pred(entry) holds (checked on arrival).
  waitFor(pred, timeoutMs, what) {
    const hit = this.log.find(pred);
    if (hit) return Promise.resolve(hit);
    return new Promise((resolve, reject) => {
      const timer = setTimeout(() => reject(new Error(`timed out after ${timeoutMs} ms waiting for ${what}`)), timeoutMs);
      this.listeners.push((e) => {
        if (!pred(e)) return false;
        clearTimeout(timer);
        resolve(e);
        return true;
      });
    });
  }

  send(msg) {
    if (!this.peer) return;
    const frame = this.protocol.serialize(msg, this.seq & 0xff);
    this.seq = (this.seq + 1) & 0xff;
    this.socket.send(frame, this.peer.port, this.peer.address);
  }

  sendHeartbeat() {
    const hb = new this.m.minimal.Heartbeat();
    hb.type = 12;       // MAV_TYPE_SUBMARINE
    hb.autopilot = 3;   // MAV_AUTOPILOT_ARDUPILOTMEGA
    hb.baseMode = CUSTOM_MODE_ENABLED | (this.armed ? ARMED_FLAG : 0);
    hb.customMode = this.customMode;
    hb.systemStatus = 4;  // MAV_STATE_ACTIVE
    hb.mavlinkVersion = 3;
    this.send(hb);
    this.lastHeartbeatMs = this.now();
  }

  // Checks one datagram as one MAVLink v2 frame: start byte, length, flags, ids, CRC_EXTRA.
  onDatagram(buf, rinfo) {
    const first = !this.peer;
    this.peer = { address: rinfo.address, port: rinfo.port };
    const t = this.now();
    const bad = (why) => { this.errors.push(why); };
    if (buf.length < 12 || buf[0] !== 0xfd) return bad(`datagram of ${buf.length} bytes is not a v2 frame`);
    const len = buf[1];
    if (buf.length !== 12 + len) return bad(`datagram ${buf.length} bytes, frame says ${12 + len}`);
    if (buf[2] !== 0 || buf[3] !== 0) return bad(`flags ${buf[2]}/${buf[3]}`);
    const seq = buf[4];
    const sender = `${buf[5]}/${buf[6]}`;
    const last = this.lastSeq.get(sender);
    if (last !== undefined && seq !== ((last + 1) & 0xff)) bad(`${sender}: sequence ${seq} after ${last}`);
    this.lastSeq.set(sender, seq);
    const from = sender === "255/190" ? "control" : sender === "1/191" ? "status" : null;
    if (!from) bad(`from ${sender}, neither 255/190 (control) nor 1/191 (status)`);
    const id = buf.readUIntLE(7, 3);
    const clazz = this.registry[id];
    if (!clazz) return bad(`unknown message id ${id}`);
    if (len < 1 || len > clazz.PAYLOAD_LENGTH) return bad(`${clazz.MSG_NAME}: length ${len}`);
    const crc = this.m.x25crc(buf, 1, 2, clazz.MAGIC_NUMBER);
    if (crc !== buf.readUInt16LE(10 + len)) return bad(`${clazz.MSG_NAME}: CRC mismatch`);
    const msg = this.protocol.data(this.protocol.payload(buf), clazz);
    const entry = { t_ms: t, id, name: clazz.MSG_NAME, msg, from };
    this.log.push(entry);
    if (from === "status") this.checkStatus(entry);
    else this.handle(entry, first);
    this.listeners = this.listeners.filter((l) => !l(entry));
  }

  handle({ id, name, msg }, first) {
    const c = this.m.common;
    if (first) this.sendHeartbeat();  // as ArduSub does once a GCS shows up (1 Hz after)
    if (id === c.ManualControl.MSG_ID) {
      if (msg.target !== 1) this.errors.push(`MANUAL_CONTROL target ${msg.target}`);
      for (const axis of ["x", "y", "r"]) {
        if (msg[axis] < -1000 || msg[axis] > 1000) this.errors.push(`MANUAL_CONTROL ${axis} = ${msg[axis]}`);
      }
      if (msg.z < 0 || msg.z > 1000) this.errors.push(`MANUAL_CONTROL z = ${msg.z}`);
    } else if (id === c.CommandLong.MSG_ID) {
      if (msg.targetSystem !== 1 || msg.targetComponent !== 1) {
        this.errors.push(`COMMAND_LONG to ${msg.targetSystem}/${msg.targetComponent}`);
      }
      if (msg.command === MAV_CMD_COMPONENT_ARM_DISARM) {
        if (msg._param1 === 1 && this.preArm) {
          this.sendPreArmFailure();
          this.ack(msg.command, 4);  // MAV_RESULT_FAILED
          return;
        }
        this.armed = msg._param1 === 1;
        this.ack(msg.command);
        this.sendHeartbeat();  // the new state at once, as ArduSub's next beat would show it
      } else if (msg.command === MAV_CMD_RUN_PREARM_CHECKS) {
        this.ack(msg.command);
        if (this.preArm) this.sendPreArmFailure();
      } else if (msg.command === MAV_CMD_DO_SET_MODE) {
        if (msg._param1 !== 1) this.errors.push(`DO_SET_MODE base mode ${msg._param1}, not custom (1)`);
        this.customMode = msg._param2;
        this.ack(msg.command);
        this.sendHeartbeat();
      } else if (msg.command === MAV_CMD_SET_MESSAGE_INTERVAL) {
        this.stream(msg._param1, msg._param2);
        this.ack(msg.command);
      } else {
        this.errors.push(`unexpected command ${msg.command}`);
      }
    } else if (id === c.ParamRequestRead.MSG_ID) {
      if (msg.targetSystem !== 1 || msg.targetComponent !== 1) {
        this.errors.push(`PARAM_REQUEST_READ to ${msg.targetSystem}/${msg.targetComponent}`);
      }
      const name = msg.paramId;
      if (msg.paramIndex === -1 && name in this.params) {
        const names = Object.keys(this.params);
        const v = Object.assign(new c.ParamValue(), {
          paramId: name, paramValue: this.params[name], paramType: 9,  // MAV_PARAM_TYPE_REAL32
          paramCount: names.length, paramIndex: names.indexOf(name) });
        this.send(v);
      }
    } else if (id !== this.m.minimal.Heartbeat.MSG_ID) {
      this.errors.push(`unexpected message ${name}`);
    }
  }

  // rovctl's status to the ground station: what Cockpit or QGroundControl would show.
  checkStatus({ id, name, msg }) {
    const bad = (why) => this.errors.push(`status ${name}: ${why}`);
    if (id === this.m.minimal.Heartbeat.MSG_ID) {
      if (msg.type !== 18) bad(`type ${msg.type}, not MAV_TYPE_ONBOARD_CONTROLLER (18)`);
      if (msg.autopilot !== 8) bad(`autopilot ${msg.autopilot}, not MAV_AUTOPILOT_INVALID (8)`);
    } else if (id === this.m.common.StatusText.MSG_ID) {
      if (msg.severity > 7) bad(`severity ${msg.severity}`);
      if (!msg.text || msg.text.length > 50) bad(`text of ${msg.text ? msg.text.length : 0} chars`);
    } else if (id === this.m.common.NamedValueFloat.MSG_ID) {
      if (!STATUS_VALUES.includes(msg.name)) bad(`name "${msg.name}"`);
    } else {
      bad("not a status message");
    }
  }

  // ArduSub's reason for refusing an arm, as its pre-arm texts come (MAV_SEVERITY_CRITICAL).
  sendPreArmFailure() {
    this.send(Object.assign(new this.m.common.StatusText(), {
      severity: 2, text: `PreArm: ${this.preArm}`, id: 0, chunkSeq: 0 }));
  }

  ack(command, result = 0) {
    this.send(Object.assign(new this.m.common.CommandAck(), {
      command, result, progress: 0, resultParam2: 0, targetSystem: 255, targetComponent: 190 }));
  }

  stream(messageId, intervalUs) {
    const c = this.m.common;
    if (this.intervals.has(messageId)) clearInterval(this.intervals.get(messageId));
    const boot = this.now();
    const make = {
      [c.AttitudeQuaternion.MSG_ID]: () => Object.assign(new c.AttitudeQuaternion(), {
        timeBootMs: Math.floor(this.now() - boot), q1: 1, q2: 0, q3: 0, q4: 0, rollspeed: 0,
        pitchspeed: 0, yawspeed: 0, reprOffsetQ: [0, 0, 0, 0] }),
      // 1 m under the surface: 1013.25 hPa + 1025 kg/m^3 * 9.81 m/s^2 * 1 m.
      [c.ScaledPressure2.MSG_ID]: () => Object.assign(new c.ScaledPressure2(), {
        timeBootMs: Math.floor(this.now() - boot), pressAbs: 1113.8, pressDiff: 0,
        temperature: 1500, temperaturePressDiff: 0 }),
      [c.SysStatus.MSG_ID]: () => Object.assign(new c.SysStatus(), {
        onboardControlSensorsPresent: 0, onboardControlSensorsEnabled: 0,
        onboardControlSensorsHealth: 0, load: 200, voltageBattery: 15800, currentBattery: 300,
        batteryRemaining: 80, dropRateComm: 0, errorsComm: 0, errorsCount1: 0, errorsCount2: 0,
        errorsCount3: 0, errorsCount4: 0 }),
    }[messageId];
    if (!make) { this.errors.push(`stream of message ${messageId} requested`); return; }
    if (intervalUs <= 0) return;
    this.intervals.set(messageId, setInterval(() => this.send(make()), Math.max(1, intervalUs / 1000)));
  }
}

// True when a MANUAL_CONTROL is neutral: no force on any axis (z 500 is neutral throttle).
// The NAMED_VALUE_FLOAT names rovctl sends (<= 10 chars, MAVLink's limit).
export const STATUS_VALUES = ["rov_state", "rov_fit", "rov_dist_m", "rov_lat_m", "rov_notok"];
export const isNeutral = (mc) => mc.x === 0 && mc.y === 0 && mc.r === 0 && mc.z === 500;
