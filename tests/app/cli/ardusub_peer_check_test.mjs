// `rovctl check` on the ArduSub bus against a fake ArduSub written with node-mavlink: it reads
// FS_PILOT_INPUT, FS_PILOT_TIMEOUT and RC_OVERRIDE_TIME by PARAM_REQUEST_READ, names each with
// whether it is safe, passes with safe values, fails (exit 2) with FS_PILOT_INPUT = 0, arms nothing;
// and the GCS id (SYSID_MYGCS, or MAV_GCS_SYSID from 4.7) against the id rovctl sends as.
// Usage: node ardusub_peer_check_test.mjs ROVCTL SOURCE_DIR WORK_DIR   (exit 77: skipped)
import { spawn } from "node:child_process";
import fs from "node:fs";
import path from "node:path";
import { FakeArduSub, loadMavlink } from "./ardusub_peer.mjs";

const [rovctl, sourceDir, workDir] = process.argv.slice(2);
const mavlink = await loadMavlink();
if (!mavlink) { console.log("SKIP: node-mavlink not installed (npm ci --prefix tests)"); process.exit(77); }

let failures = 0;
function expect(cond, what) { console.log(`${cond ? "ok" : "FAIL"}: ${what}`); if (!cond) failures++; }
fs.mkdirSync(workDir, { recursive: true });

async function check(name, params, peerOptions = {}) {
  const peer = new FakeArduSub(mavlink, { params, customMode: 0, ...peerOptions });
  const port = await peer.start();
  const config = path.join(workDir, name + ".yaml");
  fs.writeFileSync(config, [
    `calibration: ${sourceDir}/deploy/config/stereo_calibration.yaml`,
    "camera:",
    "  backend: mock",
    "thruster_bus:",
    "  backend: ardusub",
    "  ardusub:",
    `    link: udpout:127.0.0.1:${port}`,
    "    mode: wrench",
    "    ack_timeout_ms: 300",
    "sensors:",
    "  backend: ardusub",
    "",
  ].join("\n"));
  const child = spawn(rovctl, ["check", "--config", config], { stdio: ["ignore", "pipe", "pipe"] });
  let out = "";
  child.stdout.on("data", (d) => { out += d; });
  child.stderr.on("data", () => {});
  const timer = setTimeout(() => child.kill("SIGKILL"), 30000);
  const code = await new Promise((resolve) => child.on("exit", (c) => resolve(c)));
  clearTimeout(timer);
  peer.stop();
  console.log(out.split("\n").filter((l) => /ArduSub|pre-flight/.test(l)).map((l) => "  rovctl: " + l).join("\n"));
  const asked = peer.log.filter((e) => e.name === "PARAM_REQUEST_READ").map((e) => e.msg.paramId);
  expect(["FS_PILOT_INPUT", "FS_PILOT_TIMEOUT", "RC_OVERRIDE_TIME"].every((n) => asked.includes(n)),
         `${name}: PARAM_REQUEST_READ by name for the three failsafe parameters (${[...new Set(asked)].join(", ")})`);
  expect(!peer.log.some((e) => e.name === "COMMAND_LONG" && e.msg.command === 400 && e.msg._param1 === 1),
         `${name}: check arms nothing`);
  expect(peer.errors.length === 0, `${name}: every datagram valid${peer.errors.length ? " — " + peer.errors.slice(0, 3).join("; ") : ""}`);
  return { code, out };
}

{
  const { code, out } = await check("safe", { FS_PILOT_INPUT: 2, FS_PILOT_TIMEOUT: 0.5, RC_OVERRIDE_TIME: 3, SYSID_MYGCS: 255 });
  for (const n of ["FS_PILOT_INPUT", "FS_PILOT_TIMEOUT", "RC_OVERRIDE_TIME"]) {
    expect(new RegExp(`^PASS  ArduSub ${n}: `, "m").test(out), `safe values: ${n} named and PASS`);
  }
  expect(/^PASS  ArduSub SYSID_MYGCS: 255: /m.test(out), "SYSID_MYGCS 255: named and PASS");
  // The link as the tick will use it: round trip, arrivals over 1.2 s against the 20 Hz asked,
  // and the mode it is in (rovctl sets STABILIZE only when it arms).
  expect(/^PASS  ArduSub round trip: \d+ ms /m.test(out), "the link's round trip reported");
  expect(/^PASS  ArduSub HEARTBEAT: [\d.]+ Hz over 1.2 s/m.test(out), "HEARTBEAT arrivals reported");
  for (const n of ["ATTITUDE_QUATERNION", "SCALED_PRESSURE2", "SYS_STATUS"]) {
    expect(new RegExp(`^PASS  ArduSub ${n}: [\\d.]+ Hz over 1.2 s, asked 20.0 Hz`, "m").test(out),
           `${n} arriving at the rate asked`);
  }
  expect(/^PASS  ArduSub mode: custom mode 0 \(stabilize\)/m.test(out), "the mode ArduSub is in");
  expect(/^PASS  ArduSub pre-arm checks: no failure reported/m.test(out), "pre-arm checks asked, none failing");
  expect(code === 0, `safe values: rovctl check exits 0 (got ${code})`);
}
// ArduSub's pre-arm checks failing: check says ArduSub's own reason without arming.
{
  const { code, out } = await check("prearm", { FS_PILOT_INPUT: 2, FS_PILOT_TIMEOUT: 0.5, RC_OVERRIDE_TIME: 3, SYSID_MYGCS: 255 },
                                    { preArm: "Safety switch" });
  expect(/^FAIL  ArduSub pre-arm checks: PreArm: Safety switch$/m.test(out), "a PreArm failure: ArduSub's reason, FAIL");
  expect(code === 2, `a PreArm failure: rovctl check exits 2 (got ${code})`);
}
// The GCS id under both of its names (MAV_GCS_SYSID from ArduSub 4.7): a mismatch means ArduSub
// ignores every command rovctl sends.
const safeFailsafes = { FS_PILOT_INPUT: 2, FS_PILOT_TIMEOUT: 0.5, RC_OVERRIDE_TIME: 3 };
for (const [param, value, pass] of [["SYSID_MYGCS", 254, false], ["MAV_GCS_SYSID", 255, true],
                                    ["MAV_GCS_SYSID", 1, false]]) {
  const { code, out } = await check(`gcs-${param}-${value}`, { ...safeFailsafes, [param]: value });
  const line = new RegExp(`^${pass ? "PASS" : "FAIL"}  ArduSub ${param}: ${value}: `, "m");
  expect(line.test(out), `${param} ${value}: named and ${pass ? "PASS" : "FAIL"}`);
  expect(code === (pass ? 0 : 2), `${param} ${value}: rovctl check exits ${pass ? 0 : 2} (got ${code})`);
}
{
  const { code, out } = await check("unsafe", { FS_PILOT_INPUT: 0, FS_PILOT_TIMEOUT: 0.5, RC_OVERRIDE_TIME: 3 });
  expect(/^FAIL  ArduSub FS_PILOT_INPUT: 0: disabled/m.test(out), "FS_PILOT_INPUT = 0: named and FAIL (disabled)");
  expect(/^PASS  ArduSub FS_PILOT_TIMEOUT: /m.test(out), "FS_PILOT_INPUT = 0: the other parameters still judged");
  expect(code === 2, `FS_PILOT_INPUT = 0: rovctl check exits 2 (got ${code})`);
}
console.log(failures === 0 ? "PASS" : `FAIL: ${failures} check(s)`);
process.exit(failures === 0 ? 0 : 1);
