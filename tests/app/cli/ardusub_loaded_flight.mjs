// On demand: `rovctl run` on the shipped deploy/config/bluerov2-heavy.yaml against the node-mavlink
// fake ArduSub (booted in MANUAL), with only what a desk needs changed (the cameras mocked, the
// link pointed at the fake, SCHED_FIFO on or off), beside BUSY processes spinning on the CPU.
// Per flight: failsafes logged, MANUAL_CONTROL mean / median rate and longest gap, and whether
// the end was a neutral MANUAL_CONTROL and a disarm. Exit 0 when every flight had no failsafe,
// 30 +- 2 Hz mean, and ended neutral and disarmed.
// Usage: node ardusub_loaded_flight.mjs ROVCTL SOURCE_DIR WORK_DIR [--flights 3] [--seconds 60]
//        [--busy 2] [--no-sched-fifo]
import { spawn } from "node:child_process";
import fs from "node:fs";
import path from "node:path";
import { FakeArduSub, isNeutral, loadMavlink } from "./ardusub_peer.mjs";

const [rovctl, sourceDir, workDir, ...rest] = process.argv.slice(2);
const option = (name, fallback) => {
  const i = rest.indexOf(name);
  return i >= 0 ? Number(rest[i + 1]) : fallback;
};
const flights = option("--flights", 3);
const seconds = option("--seconds", 60);
const busy = option("--busy", 2);
const schedFifo = !rest.includes("--no-sched-fifo");
const mavlink = await loadMavlink();
if (!mavlink) { console.log("SKIP: node-mavlink not installed (npm ci --prefix tests)"); process.exit(77); }
fs.mkdirSync(workDir, { recursive: true });

// The shipped file, with the camera backend, the link and the scheduler's SCHED_FIFO changed.
function writeConfig(name, port) {
  const shipped = fs.readFileSync(path.join(sourceDir, "deploy/config/bluerov2-heavy.yaml"), "utf8");
  const text = shipped
    .replace(/^calibration: .*$/m, `calibration: ${sourceDir}/deploy/config/stereo_calibration.yaml`)
    .replace(/^  backend: v4l2$/m, "  backend: mock")
    .replace(/^    link: udpin:.*$/m, `    link: udpout:127.0.0.1:${port}`)
    .replace(/^    sched_fifo: true$/m, `    sched_fifo: ${schedFifo}`)
    .replace(/^    cpu_affinity: 1$/m, schedFifo ? "    cpu_affinity: 1" : "    cpu_affinity: -1");
  const file = path.join(workDir, `${name}.yaml`);
  fs.writeFileSync(file, text);
  return file;
}

const spinners = [];
for (let i = 0; i < busy; ++i) spinners.push(spawn("sh", ["-c", "while :; do :; done"], { stdio: "ignore" }));
process.on("exit", () => { for (const s of spinners) s.kill("SIGKILL"); });

let failures = 0;
for (let n = 0; n < flights; ++n) {
  const name = `flight_${n}`;
  const peer = new FakeArduSub(mavlink, { customMode: 19 });
  const port = await peer.start();
  const child = spawn(rovctl, ["run", "--config", writeConfig(name, port)], { stdio: ["ignore", "ignore", "pipe"] });
  let log = "";
  child.stderr.on("data", (d) => { log += d; });
  const exited = new Promise((resolve) => child.on("exit", (code) => resolve(code)));
  await new Promise((r) => setTimeout(r, seconds * 1000));
  const stopAt = peer.now();
  child.kill("SIGTERM");
  const code = await Promise.race([exited, new Promise((r) => setTimeout(() => r("timeout"), 10000))]);
  if (code === "timeout") child.kill("SIGKILL");
  peer.stop();
  fs.writeFileSync(path.join(workDir, `${name}.log`), log);
  const armAt = peer.log.find((e) => e.name === "COMMAND_LONG" && e.msg.command === 400 && e.msg._param1 === 1);
  const mc = peer.log.filter((e) => e.name === "MANUAL_CONTROL" && armAt && e.t_ms > armAt.t_ms && e.t_ms < stopAt);
  const gaps = mc.slice(1).map((e, i) => e.t_ms - mc[i].t_ms).sort((a, b) => a - b);
  const meanHz = mc.length > 1 ? 1000 * (mc.length - 1) / (mc[mc.length - 1].t_ms - mc[0].t_ms) : 0;
  const medianHz = gaps.length ? 1000 / gaps[Math.floor(gaps.length / 2)] : 0;
  const maxGap = gaps.length ? gaps[gaps.length - 1] : NaN;
  const failsafes = log.split("\n").filter((l) => /FAILSAFE/.test(l));
  const lastMc = peer.log.filter((e) => e.name === "MANUAL_CONTROL").pop();
  const disarmed = peer.log.some((e) => e.name === "COMMAND_LONG" && e.msg.command === 400 && e.msg._param1 === 0 && e.t_ms >= stopAt);
  const ok = armAt && failsafes.length === 0 && Math.abs(meanHz - 30) <= 2 && lastMc && isNeutral(lastMc.msg) && disarmed && code === 0;
  if (!ok) failures++;
  console.log(JSON.stringify({
    flight: n, seconds, busy, sched_fifo: schedFifo, armed: Boolean(armAt), exit: code,
    failsafes: failsafes.length, first_failsafe: failsafes[0] || null,
    manual_control: mc.length, mean_hz: +meanHz.toFixed(2), median_hz: +medianHz.toFixed(2),
    longest_gap_ms: +maxGap.toFixed(1), ended_neutral: Boolean(lastMc && isNeutral(lastMc.msg)),
    disarmed_at_end: disarmed, datagram_errors: peer.errors.length, ok: Boolean(ok),
  }));
}
process.exit(failures === 0 ? 0 : 1);
