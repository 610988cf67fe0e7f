// The operator view in a real browser: Debian's chromium, driven by puppeteer-core, against
// `rovctl sim --serve`. Checks that the page loads, the camera stream updates, the state goes
// from SEARCH (held until START from the page) to DOCKED past passing bars (the banner names why a
// view is not trusted), ABORT without the token is refused (403) and changes nothing, and ABORT
// from the page puts the vehicle in neutral within 2 ticks (read back from the run's telemetry).
// Usage: node operator_view_browser_test.mjs ROVCTL ARTIFACT_DIR   (exit 77: skipped)
import { spawn } from "node:child_process";
import fs from "node:fs";
import path from "node:path";

const [rovctl, artifacts] = process.argv.slice(2);
const chromium = process.env.CHROMIUM || "/usr/bin/chromium";
const TOKEN = "test-token-7f3a";
const HOLD_BIT = 1 << 10;

function skip(why) { console.log("SKIP: " + why); process.exit(77); }
function fail(why) { console.error("FAIL: " + why); process.exit(1); }
function check(cond, what) { if (!cond) fail(what); console.log("ok: " + what); }
const sleep = (ms) => new Promise((r) => setTimeout(r, ms));

if (!fs.existsSync(chromium)) skip(`no chromium at ${chromium} (apt-get install chromium)`);
let puppeteer;
try { puppeteer = (await import("puppeteer-core")).default; }
catch { skip("puppeteer-core not installed (npm ci --prefix tests)"); }
fs.mkdirSync(artifacts, { recursive: true });

// Starts a served sim and resolves with its URL once rovctl prints it.
function serve(extra) {
  const child = spawn(rovctl, ["sim", "--serve", "127.0.0.1:0", "--token", TOKEN, "--trials", "1",
                               ...extra], { stdio: ["ignore", "pipe", "pipe"] });
  let log = "";
  const url = new Promise((resolve, reject) => {
    child.stderr.on("data", (d) => {
      log += d;
      const m = /operator view at (http:\/\/\S+)/.exec(log);
      if (m) resolve(m[1]);
    });
    child.on("exit", (code) => reject(new Error(`rovctl exited ${code} before serving:\n${log}`)));
  });
  const exited = new Promise((resolve) => child.on("exit", (code) => resolve(code)));
  return { child, url, exited, log: () => log };
}

async function waitFor(page, fn, arg, timeout_ms, what) {
  try { await page.waitForFunction(fn, { timeout: timeout_ms, polling: 100 }, arg); }
  catch { fail(`timed out after ${timeout_ms} ms waiting for ${what}`); }
}

const browser = await puppeteer.launch({
  executablePath: chromium, headless: true,
  args: ["--no-sandbox", "--disable-gpu", "--disable-dev-shm-usage"],
});
try {
  // --- 1. A docking run, watched from SEARCH to DOCKED. ---
  // --hold: the vehicle waits in SEARCH for START, so the page sees the mission from its start
  // however slowly the browser comes up (on a loaded CI machine it used to miss SEARCH).
  // Passing bars (the occluders scenario) hide a sphere now and then: the page must say so.
  const run = serve(["--seed", "3", "--serve-linger", "6", "--max-time", "120", "--hold",
                     "--scenario", "occluders"]);
  const url = await run.url;
  const page = await browser.newPage();
  await page.setViewport({ width: 1400, height: 820 });
  await page.goto(url + "?token=" + TOKEN, { waitUntil: "domcontentloaded" });
  await waitFor(page, () => window.rovctl && window.rovctl.updates > 0, null, 20000, "first state");
  const first = await page.evaluate(() => [window.rovctl.seenStates[0], window.rovctl.last.operator_hold]);
  check(first[0] === "SEARCH" && first[1], `first state shown is SEARCH, held (got ${first})`);
  await page.click("#start");
  await waitFor(page, () => /START: 200/.test(document.getElementById("cmd").textContent), null,
                5000, "START accepted");
  await waitFor(page, () => !window.rovctl.last.operator_hold, null, 5000, "the hold released");
  await waitFor(page, () => document.getElementById("cams").naturalWidth > 0, null, 20000,
                "the first camera picture");
  const cams = await page.$("#cams");
  const a = await cams.screenshot();
  await sleep(1500);
  const b = await cams.screenshot();
  check(Buffer.compare(a, b) !== 0, "the camera stream updates (two pictures 1.5 s apart differ)");
  // The picture for the README: close in, the outlines on the spheres.
  await waitFor(page, () => ["DOCK", "DOCKED"].includes(window.rovctl.seenStates.at(-1)),
                null, 120000, "DOCK");
  await page.screenshot({ path: path.join(artifacts, "operator_view.png") });
  await waitFor(page, () => window.rovctl.seenStates.includes("DOCKED"), null, 120000, "DOCKED");
  const seen = await page.evaluate(() => window.rovctl.seenStates);
  check(seen.indexOf("SEARCH") < seen.indexOf("DOCKED"),
        `states seen in order: ${seen.join(" -> ")}`);
  await page.screenshot({ path: path.join(artifacts, "operator_view_docked.png") });
  // Whenever the estimate was not ok, the banner said which test failed, in the page's words.
  const notOk = await page.evaluate(() => window.rovctl.notOkShown);
  const label = { partial_view: "PARTIAL VIEW", not_refined: "NOT REFINED",
                  bound_over_limit: "BOUND OVER LIMIT", unconfirmed: "UNCONFIRMED" };
  check(Object.keys(notOk).length > 0 &&
        Object.entries(notOk).every(([reason, text]) => label[reason] === text),
        `the not-ok banner shown, naming its reason (${JSON.stringify(notOk)})`);
  const code = await run.exited;
  check(code === 0, `rovctl sim --serve exits 0 (got ${code})`);

  // --- 2. ABORT: refused without the token, then accepted from the page. ---
  const out = fs.mkdtempSync(path.join(artifacts, "abort-run-"));
  const run2 = serve(["--seed", "4", "--serve-linger", "1", "--max-time", "25", "--out", out]);
  const url2 = await run2.url;
  const page2 = await browser.newPage();
  await page2.goto(url2 + "?token=" + TOKEN, { waitUntil: "domcontentloaded" });
  await waitFor(page2, () => window.rovctl && window.rovctl.last &&
                window.rovctl.last.thrust_fraction.some((v) => Math.abs(v) > 0.01),
                null, 30000, "thrust");
  const refused = await page2.evaluate(async () => {
    const r = await fetch("/abort", { method: "POST", headers: { "X-Rovctl-Token": "wrong" } });
    const bare = await fetch("/abort", { method: "POST" });
    return [r.status, bare.status];
  });
  check(refused[0] === 403 && refused[1] === 403,
        `ABORT with a wrong or no token is refused: ${refused.join(", ")}`);
  await sleep(700);
  const after = await page2.evaluate(() => window.rovctl.last);
  check(!after.operator_hold && after.thrust_fraction.some((v) => Math.abs(v) > 0.01),
        "after the refused ABORT the vehicle still flies (no hold, thrust on)");
  await page2.click("#abort");
  await waitFor(page2, () => /ABORT: 200/.test(document.getElementById("cmd").textContent), null,
                5000, "ABORT accepted");
  const answer = await page2.evaluate(() => document.getElementById("cmd").textContent);
  const abortTick = Number(/"tick":\s*(\d+)/.exec(answer)[1]);
  await waitFor(page2, () => window.rovctl.last.operator_hold &&
                window.rovctl.last.thrust_fraction.every((v) => v === 0), null, 5000,
                "the hold banner and neutral thrust on the page");
  await page2.screenshot({ path: path.join(artifacts, "operator_view_abort.png") });
  await run2.exited;

  // The run's own telemetry: the first held tick, and neutral from there on.
  const csv = fs.readFileSync(path.join(out, "trial_000.csv"), "utf8").trim().split("\n");
  const head = csv[0].split(",");
  const col = (n) => head.indexOf(n);
  const rows = csv.slice(1).map((l) => l.split(","));
  const held = rows.filter((r) => (Number(r[col("flags")]) & HOLD_BIT) !== 0);
  check(held.length > 0, "the telemetry records the operator hold");
  const firstHeld = Number(held[0][col("tick")]);
  const before = rows.filter((r) => Number(r[col("tick")]) < firstHeld);
  check(before.every((r) => (Number(r[col("flags")]) & HOLD_BIT) === 0),
        "no hold before the accepted ABORT (the refused ones changed nothing)");
  check(firstHeld - abortTick <= 2,
        `neutral within 2 ticks of the ABORT: requested at tick ${abortTick}, held from ${firstHeld}`);
  const cmds = [0, 1, 2, 3, 4, 5, 6, 7].map((i) => col("cmd" + i));
  check(held.every((r) => cmds.every((c) => Number(r[c]) === 0)),
        `every held tick (${held.length}) commands zero thrust`);
} finally {
  await browser.close();
}
console.log("PASS");
