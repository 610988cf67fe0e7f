// `rovctl run` on the ArduSub bus and sensors against a fake ArduSub written with node-mavlink:
// ids, lengths, CRCs, 255/190 -> 1/1, axis ranges, the 30 Hz rate, neutral + disarm on SIGTERM,
// and safe within 2 ticks when the peer's HEARTBEAT stops, it goes silent altogether or it reports
// itself disarmed; booted in MANUAL it is set to the flight mode before the arm, and a PreArm
// refusal is in rovctl's error; and the status to the ground station (1/191): HEARTBEAT at 1 Hz,
// the four values at 4 Hz, a STATUSTEXT naming each failsafe.
// Usage: node ardusub_peer_run_test.mjs ROVCTL SOURCE_DIR WORK_DIR   (exit 77: skipped)
import { spawn } from "node:child_process";
import fs from "node:fs";
import os from "node:os";
import path from "node:path";
import { FakeArduSub, isNeutral, loadMavlink, STATUS_VALUES } from "./ardusub_peer.mjs";

const [rovctl, sourceDir, workDir] = process.argv.slice(2);
const mavlink = await loadMavlink();
if (!mavlink) { console.log("SKIP: node-mavlink not installed (npm ci --prefix tests)"); process.exit(77); }

const PERIOD_MS = 33;            // scheduler.period_ms
const LINK_TIMEOUT_MS = 1500;    // thruster_bus.ardusub.link_timeout_ms
const STREAM_TIMEOUT_MS = 200;   // thruster_bus.ardusub.stream_timeout_ms
let failures = 0;
function expect(cond, what) { console.log(`${cond ? "ok" : "FAIL"}: ${what}`); if (!cond) failures++; }
// Checks a starved machine could not judge: the test then reports itself skipped (exit 77, with
// the load measured), never passed, unless another check failed.
const notJudged = [];

fs.mkdirSync(workDir, { recursive: true });
// A failed wait ends the test: no rovctl may outlive it.
const children = new Set();
process.on("exit", () => { for (const c of children) c.kill("SIGKILL"); });
process.on("unhandledRejection", (e) => { console.error("FAIL: " + e.message); process.exit(1); });

function writeConfig(name, port) {
  const file = path.join(workDir, name + ".yaml");
  fs.writeFileSync(file, [
    `calibration: ${sourceDir}/deploy/config/stereo_calibration.yaml`,
    "camera:",
    "  backend: mock        # the simulator's rendered cameras: no camera hardware here",
    "thruster_bus:",
    "  backend: ardusub",
    "  ardusub:",
    `    link: udpout:127.0.0.1:${port}`,
    "    mode: wrench",
    "    flight_mode: stabilize",
    `    link_timeout_ms: ${LINK_TIMEOUT_MS}`,
    `    stream_timeout_ms: ${STREAM_TIMEOUT_MS}`,
    "    ack_timeout_ms: 300",
    "  timing:",
    "    degraded_ms: 1000",
    "    watchdog_ms: 2000",
    "sensors:",
    "  backend: ardusub",
    "  ardusub:",
    "    stream_interval_ms: 50",
    "    stale_ms: 2000",
    "estimator:",
    "  budget: time        # the GA takes what its budget allows: the tick holds 33 ms on a loaded bench",
    // What a starved machine (ctest -j2, ASan) trips on its own is relaxed, so that the failsafes
    // under test are the link's and ArduSub's: CPU overruns, stale sensors and the I/O thread's
    // send gap. The ArduSub bus's own fault (HEARTBEAT lost, disarmed, mode) is untouched.
    "control:",
    "  failsafe:",
    "    overrun_ticks: 1000",
    "    stale_ms: 2000",
    "    bus_degraded_ticks: 1000",
    // As on the vehicle (deploy/config/bluerov2-heavy.yaml): opt-in here, since a shared CI
    // machine should not give a test's tick SCHED_FIFO; refused without CAP_SYS_NICE (a warning).
    ...(process.env.ROVCTL_PEER_SCHED_FIFO === "1"
      ? ["scheduler:", "  realtime:", "    sched_fifo: true", "    priority: 50"] : []),
    "",
  ].join("\n"));
  return file;
}

// Starts rovctl run against a fresh peer; resolves once the peer acknowledged the arm.
async function startRun(name, peerOptions = {}) {
  // Booted as ArduSub boots, in MANUAL (19): rovctl must ask for its flight_mode before it arms.
  const peer = new FakeArduSub(mavlink, { customMode: 19, ...peerOptions });
  const port = await peer.start();
  const config = writeConfig(name, port);
  const child = spawn(rovctl, ["run", "--config", config, "--telemetry", path.join(workDir, name + ".csv")],
                      { stdio: ["ignore", "ignore", "pipe"] });
  let stderr = "";
  const logFile = fs.createWriteStream(path.join(workDir, name + ".log"));
  child.stderr.on("data", (d) => { stderr += d; logFile.write(d); });
  children.add(child);
  child.on("exit", () => children.delete(child));
  const exited = new Promise((resolve) => child.on("exit", (code, signal) => resolve({ code, signal })));
  const armedAt = await peer.waitFor((e) => e.name === "COMMAND_LONG" && e.msg.command === 400 && e.msg._param1 === 1,
                                     20000, "the arm command");
  const setMode = peer.log.find((e) => e.name === "COMMAND_LONG" && e.msg.command === 176);
  expect(setMode && setMode.t_ms <= armedAt.t_ms && setMode.msg._param2 === 0 && peer.customMode === 0,
         `${name}: booted in MANUAL, rovctl set STABILIZE (DO_SET_MODE custom mode 0) before it armed`);
  return { name, peer, child, exited, armedAt, stderr: () => stderr };
}

const manuals = (peer, fromMs) => peer.log.filter((e) => e.name === "MANUAL_CONTROL" && e.t_ms > fromMs);
let rateFigures = null;
// The exit code rovctl documents: 1 when a failsafe is tripped when it stops, else 0. A
// transient one (CPU overrun on a starved machine) may be active at SIGTERM: the log says which.
function expectExit(result, log, what) {
  const lines = log.split("\n").filter((l) => /FAILSAFE/.test(l));
  const tripped = lines.length > 0 && !/recovered/.test(lines[lines.length - 1]);
  expect(result.code === (tripped ? 1 : 0),
         `${what}: rovctl run exits ${tripped ? "1 (a failsafe tripped at the end, logged)" : "0"} (got ${result.code}${result.signal ? ", " + result.signal : ""})`);
}
const median = (xs) => { const s = [...xs].sort((a, b) => a - b); return s[Math.floor(s.length / 2)]; };

async function finish(run, what) {
  run.child.kill("SIGTERM");
  const result = await Promise.race([run.exited, new Promise((r) => setTimeout(() => r({ code: "timeout" }), 10000))]);
  if (result.code === "timeout") run.child.kill("SIGKILL");
  run.peer.stop();
  expect(run.peer.errors.length === 0,
         `${what}: every datagram a valid v2 frame, control from 255/190 and status from 1/191, a known id, ` +
         `its length and CRC, each sender in sequence, addressed to 1/1, axes in range${run.peer.errors.length ? " — " + run.peer.errors.slice(0, 5).join("; ") : ""}`);
  return result;
}

// 1. Rate, ranges, ids; then SIGTERM: a neutral MANUAL_CONTROL, then the disarm, then exit 0.
{
  const run = await startRun("rate");
  const first = await run.peer.waitFor((e) => e.name === "MANUAL_CONTROL" && e.t_ms > run.armedAt.t_ms, 5000, "MANUAL_CONTROL");
  await run.peer.waitFor(() => manuals(run.peer, first.t_ms - 1).length >= 301, 30000, "301 MANUAL_CONTROL");
  const mc = manuals(run.peer, first.t_ms - 1).slice(0, 301);
  const gaps = mc.slice(1).map((e, i) => e.t_ms - mc[i].t_ms);
  rateFigures = { medianHz: 1000 / median(gaps), meanHz: 1000 * gaps.length / (mc[300].t_ms - mc[0].t_ms),
                  maxGapMs: Math.max(...gaps) };
  expect(mc.some((e) => !isNeutral(e.msg)), "the armed vehicle commands forces (not only neutral)");
  // The status, over the same 300 ticks (about 10 s): 1 Hz and 4 Hz, within a loaded machine's slack.
  const statusSpanS = (mc[300].t_ms - mc[0].t_ms) / 1000;
  const status = run.peer.log.filter((e) => e.from === "status" && e.t_ms >= mc[0].t_ms && e.t_ms <= mc[300].t_ms);
  const beats = status.filter((e) => e.name === "HEARTBEAT").length;
  expect(beats >= Math.floor(statusSpanS) - 1 && beats <= Math.ceil(statusSpanS) + 1,
         `status HEARTBEAT from 1/191 (onboard controller) at 1 Hz: ${beats} in ${statusSpanS.toFixed(1)} s`);
  for (const name of STATUS_VALUES) {
    const n = status.filter((e) => e.name === "NAMED_VALUE_FLOAT" && e.msg.name === name).length;
    expect(n >= 3 * statusSpanS && n <= 5 * statusSpanS,
           `status NAMED_VALUE_FLOAT ${name} at about 4 Hz: ${n} in ${statusSpanS.toFixed(1)} s`);
  }
  // rov_notok is estimator::NotOkReason's id (0 ok, 1 partial view, 2 not refined, 3 bound over
  // the limit, 4 unconfirmed), NaN before the first pair: read by node-mavlink, not our decoder.
  const reasons = status.filter((e) => e.name === "NAMED_VALUE_FLOAT" && e.msg.name === "rov_notok")
    .map((e) => e.msg.value);
  expect(reasons.length > 0 && reasons.every((v) => Number.isNaN(v) || [0, 1, 2, 3, 4].includes(v)),
         `rov_notok holds a reason id: ${[...new Set(reasons.map(String))].join(", ")}`);
  const sigtermAt = run.peer.now();
  const result = await finish(run, "SIGTERM run");
  const after = run.peer.log.filter((e) => e.t_ms >= sigtermAt);
  const disarm = after.findIndex((e) => e.name === "COMMAND_LONG" && e.msg.command === 400 && e.msg._param1 === 0);
  const neutralBefore = after.slice(0, Math.max(disarm, 0)).findIndex((e) => e.name === "MANUAL_CONTROL" && isNeutral(e.msg));
  const forcesAfter = after.slice(Math.max(disarm, 0)).filter((e) => e.name === "MANUAL_CONTROL" && !isNeutral(e.msg));
  expect(disarm >= 0 && neutralBefore >= 0 && forcesAfter.length === 0,
         `SIGTERM: a neutral MANUAL_CONTROL, then ARM_DISARM(0), and no force after it`);
  expectExit(result, run.stderr(), "SIGTERM");
  // The rate is judged on the peer. When rovctl's own scheduler says the machine starved it
  // (more than 5 % of the 33 ms releases skipped by overruns, as under ctest -j2 with ASan),
  // the peer's rate says nothing about rovctl: then it is reported, not asserted, and what is
  // asserted is that the ticks rovctl did run sent their MANUAL_CONTROL.
  const sched = /scheduler: (\d+) ticks of [\d.]+ ms, \d+ overrun ticks, (\d+) skipped releases/.exec(run.stderr());
  const ticks = sched ? +sched[1] : 0;
  const skipped = sched ? +sched[2] : 0;
  const skippedShare = skipped / Math.max(1, ticks + skipped);
  const { medianHz, meanHz, maxGapMs } = rateFigures;
  const figures = `median ${medianHz.toFixed(2)} Hz, mean ${meanHz.toFixed(2)} Hz, longest gap ${maxGapMs.toFixed(1)} ms; ` +
                  `rovctl: ${ticks} ticks, ${skipped} releases skipped`;
  if (skippedShare <= 0.05) {
    expect(medianHz >= 28 && medianHz <= 32, `MANUAL_CONTROL rate over 300 intervals within 30 +- 2 Hz (${figures})`);
  } else {
    const sent = manuals(run.peer, run.armedAt.t_ms).length;
    const load = os.loadavg().map((l) => l.toFixed(2)).join(" ");
    notJudged.push(`MANUAL_CONTROL rate not judged: the machine starved rovctl (${(100 * skippedShare).toFixed(0)} % ` +
                   `of releases skipped, load average ${load} on ${os.cpus().length} CPUs): ${figures}`);
    console.log(`NOTE: ${notJudged[notJudged.length - 1]}`);
    // The I/O thread sends only the newest command and drops one older than 66 ms: a starved
    // thread may skip a few, hence 90 %.
    expect(sent >= 0.9 * ticks, `a MANUAL_CONTROL per tick while starved (${sent} received, ${ticks} ticks, at least 90 %)`);
  }
}

// The peer's trigger -> the first neutral MANUAL_CONTROL, counted in MANUAL_CONTROLs (ticks) that
// still carried a force after the trigger; the rovctl log must name the failsafe.
async function safeWithin2Ticks(name, what, trigger, triggerMs, delayMs, expectLog) {
  const run = await startRun(name);
  // Pull the trigger once rovctl has commanded forces for 5 ticks in a row (a failsafe of its own
  // from a starved start-up may hold it neutral for a while), so that neutral is a change.
  const forcing = await run.peer.waitFor(() => {
    const mc = manuals(run.peer, run.armedAt.t_ms).slice(-5);
    return mc.length === 5 && mc.every((e) => !isNeutral(e.msg));
  }, 20000, "5 MANUAL_CONTROL in a row with force").then(() => true, () => false);
  const pulled = trigger(run.peer);
  const t0 = await triggerMs(run.peer, pulled);
  await run.peer.waitFor((e) => e.t_ms > t0 && e.name === "MANUAL_CONTROL" && isNeutral(e.msg),
                         t0 - run.peer.now() + 5000, "a neutral MANUAL_CONTROL").catch((e) => e);
  await new Promise((r) => setTimeout(r, 300));  // what follows must stay neutral
  const after = manuals(run.peer, t0);
  const firstNeutral = after.findIndex((e) => isNeutral(e.msg));
  const stayed = firstNeutral >= 0 && after.slice(firstNeutral).every((e) => isNeutral(e.msg));
  const lateMs = firstNeutral >= 0 ? after[firstNeutral].t_ms - t0 : NaN;
  // The same count from the earliest moment rovctl could have acted (the beat's send time + delay).
  const fromEarliest = manuals(run.peer, pulled + delayMs).findIndex((e) => isNeutral(e.msg));
  const result = await finish(run, what);
  expect(forcing, `${what}: 5 MANUAL_CONTROL in a row with force before the trigger (so neutral is a change)`);
  expect(firstNeutral >= 0 && firstNeutral <= 2 && stayed,
         `${what}: neutral within 2 ticks (${firstNeutral} MANUAL_CONTROL with force after the trigger, ` +
         `first neutral ${lateMs.toFixed(1)} ms after it; ${fromEarliest} counted from the beat's send time) ` +
         `and neutral from then on`);
  expect(expectLog.test(run.stderr()), `${what}: rovctl logged the failsafe (${expectLog})`);
  const told = run.peer.log.find((e) => e.from === "status" && e.name === "STATUSTEXT" && e.t_ms > t0 - 100 &&
                                        /FAILSAFE/.test(e.msg.text));
  expect(told && told.msg.severity <= 4,
         `${what}: the ground station told (STATUSTEXT${told ? ` "${told.msg.text}", severity ${told.msg.severity}` : " missing"})`);
  expect(result.code === 1, `${what}: rovctl run exits 1 after a failsafe trip (got ${result.code})`);
}

// 2. The peer stops beating. rovctl reads its link in each tick's write, just before that tick's
// MANUAL_CONTROL, so the first MANUAL_CONTROL after the peer's last HEARTBEAT marks when rovctl had
// it; the link is declared lost LINK_TIMEOUT_MS after that, and the 2 ticks count from there.
await safeWithin2Ticks("heartbeat", "HEARTBEAT stops",
                       (peer) => { peer.beating = false; return peer.lastHeartbeatMs; },
                       async (peer, last) => (await peer.waitFor((e) => e.name === "MANUAL_CONTROL" && e.t_ms > last,
                                                                 5000, "the MANUAL_CONTROL after the last HEARTBEAT")).t_ms + LINK_TIMEOUT_MS,
                       LINK_TIMEOUT_MS, /FAILSAFE thruster bus fault \(ArduSub link lost: no HEARTBEAT for \d+ ms/);
// 3. The peer reports disarmed (base_mode without SAFETY_ARMED): the 2 ticks count from that beat.
await safeWithin2Ticks("disarmed", "ArduSub reports disarmed",
                       (peer) => { peer.armed = false; peer.sendHeartbeat(); return peer.lastHeartbeatMs; },
                       async (peer, sent) => sent, 0, /FAILSAFE thruster bus fault \(ArduSub disarmed\)/);

// 4. ArduSub goes silent (HEARTBEAT and every stream stop): the attitude stream, asked at 20 Hz,
// tells it STREAM_TIMEOUT_MS after its last message, long before the 1 Hz HEARTBEAT can.
await safeWithin2Ticks("silent", "ArduSub silent",
                       (peer) => peer.silence(),
                       async (peer, last) => last + STREAM_TIMEOUT_MS, STREAM_TIMEOUT_MS,
                       /FAILSAFE thruster bus fault \(ArduSub silent: no ATTITUDE_QUATERNION for \d+ ms/);
// 5. ArduSub refuses to arm with a pre-arm reason: rovctl exits saying ArduSub's words.
{
  const run = await startRun("prearm", { preArm: "Safety switch" });
  const result = await Promise.race([run.exited, new Promise((r) => setTimeout(() => r({ code: "timeout" }), 10000))]);
  if (result.code === "timeout") run.child.kill("SIGKILL");
  run.peer.stop();
  expect(result.code !== 0 && result.code !== "timeout", `PreArm refusal: rovctl run exits non-zero (got ${result.code})`);
  expect(/could not arm the thrusters \(ArduSub refused arm \(MAV_RESULT 4\): PreArm: Safety switch\)/.test(run.stderr()),
         `PreArm refusal: the reason in rovctl's error (${run.stderr().split("\n").filter((l) => /arm/.test(l)).join(" | ")})`);
  expect(!run.peer.armed, "PreArm refusal: never armed");
}

if (failures > 0) {
  console.log(`FAIL: ${failures} check(s)`);
  process.exit(1);
}
if (notJudged.length > 0) {
  console.log(`SKIP: ${notJudged.join("; ")}`);
  process.exit(77);
}
console.log("PASS");
process.exit(0);
