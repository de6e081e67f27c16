#!/usr/bin/python3
"""Checks vdrive's web page in a real browser: headless Chromium driven over the Chrome DevTools
Protocol (CDP) with nothing but Debian's python3-websocket.

It opens the page served by `vdrive ... --web`, then, as a user would with the page's own
controls:
  1. waits until every slave box of the network picture has shown Op (data-al-state 8, "Op");
  2. reads an axis plot's data through Chart.js and checks that points keep arriving and move;
  3. measures the live updates per second the page receives;
  4. starts a fault with the faults panel's button and waits for the drive's alarm on the page;
  5. writes a read-only object (6041h:00) with the object-dictionary panel and waits for the
     refusal with its SDO abort code;
  6. saves a screenshot.
What it saw goes to --result as JSON (the alarm's 603Fh, for the caller to find in DDS telemetry).
Exit 0: every check held; 1: one failed (the message says which and what the page showed);
77: Chromium or the websocket module is missing.

Usage: cdp_page_check.py --url http://127.0.0.1:8080/ --slaves 3 --fault overload --fault-slave 1
                         [--expect-alarm 16.0] [--screenshot FILE] [--result FILE] [--chromium PATH]
"""
import argparse
import base64
import json
import os
import shutil
import subprocess
import sys
import tempfile
import time
import urllib.request

try:
    import websocket  # Debian python3-websocket (websocket-client)
except ImportError:
    print("SKIP: python3-websocket is not installed")
    sys.exit(77)


class CheckFailed(Exception):
    pass


class Cdp:
    """One CDP session over the page target's WebSocket: numbered calls, events kept aside."""

    def __init__(self, ws_url):
        # Chromium refuses DevTools WebSockets that carry an Origin it was not told to allow.
        self.ws = websocket.create_connection(ws_url, suppress_origin=True, timeout=30)
        self.next_id = 0
        self.exceptions = []

    def call(self, method, **params):
        self.next_id += 1
        my_id = self.next_id
        self.ws.send(json.dumps({"id": my_id, "method": method, "params": params}))
        while True:
            msg = json.loads(self.ws.recv())
            if msg.get("id") == my_id:
                if "error" in msg:
                    raise CheckFailed(f"CDP {method}: {msg['error']}")
                return msg.get("result", {})
            if msg.get("method") == "Runtime.exceptionThrown":
                d = msg["params"]["exceptionDetails"]
                self.exceptions.append((d.get("exception") or {}).get("description") or d.get("text"))

    def eval(self, expression):
        r = self.call("Runtime.evaluate", expression=expression, returnByValue=True, awaitPromise=True)
        if "exceptionDetails" in r:
            d = r["exceptionDetails"]
            raise CheckFailed(f"page script failed: {(d.get('exception') or {}).get('description') or d.get('text')}\n  in: {expression}")
        return r["result"].get("value")

    def wait_for(self, expression, timeout, what, show=None):
        """Polls until the expression is truthy; on timeout fails with what the page shows."""
        deadline = time.monotonic() + timeout
        while True:
            value = self.eval(expression)
            if value:
                return value
            if time.monotonic() > deadline:
                seen = self.eval(show) if show else value
                raise CheckFailed(f"{what} within {timeout} s; the page shows: {seen}")
            time.sleep(0.1)

    def close(self):
        self.ws.close()


def js(s):
    return json.dumps(s)


def start_chromium(chromium, profile):
    # Port 0: Chromium picks a free port and writes it to DevToolsActivePort in the profile.
    args = [chromium, "--headless=new", "--no-sandbox", "--disable-gpu", "--no-first-run",
            "--no-default-browser-check", "--disable-extensions", "--disable-background-networking",
            "--remote-debugging-port=0", f"--user-data-dir={profile}", "--window-size=1600,1000", "about:blank"]
    log = open(os.path.join(profile, "chromium.log"), "w")
    proc = subprocess.Popen(args, stdout=log, stderr=subprocess.STDOUT, start_new_session=True)
    port_file = os.path.join(profile, "DevToolsActivePort")
    deadline = time.monotonic() + 30
    while time.monotonic() < deadline:
        if proc.poll() is not None:
            raise CheckFailed(f"chromium exited {proc.returncode}: {open(log.name).read()[-2000:]}")
        try:
            with open(port_file) as f:
                port = int(f.readline().strip())
            break
        except (OSError, ValueError):
            time.sleep(0.1)
    else:
        raise CheckFailed("chromium did not open its DevTools port within 30 s")
    deadline = time.monotonic() + 15
    while True:
        try:
            with urllib.request.urlopen(f"http://127.0.0.1:{port}/json/list", timeout=5) as r:
                pages = [t for t in json.load(r) if t.get("type") == "page"]
            if pages:
                return proc, pages[0]["webSocketDebuggerUrl"]
        except OSError:
            pass
        if time.monotonic() > deadline:
            raise CheckFailed("chromium shows no page target")
        time.sleep(0.2)


def wait_for_server(url, timeout):
    deadline = time.monotonic() + timeout
    last = None
    while time.monotonic() < deadline:
        try:
            with urllib.request.urlopen(url.rstrip("/") + "/api/v1/line", timeout=5) as r:
                json.load(r)
                return
        except (OSError, ValueError) as e:
            last = e
            time.sleep(0.25)
    raise CheckFailed(f"no vdrive web server at {url} within {timeout} s ({last})")


SLAVES_SHOWN = """[...document.querySelectorAll('#net-strip .slave')].map(b =>
  b.dataset.slave + ':' + b.dataset.alState + ':' + b.querySelector('.sl-al-state').textContent).join(' ')"""


def check_slaves_op(cdp, n, timeout):
    """Every slave box shows Op (not necessarily at the same poll: a host stall may take the line
    out of Op later, which the steps after this one notice)."""
    seen = set()
    deadline = time.monotonic() + timeout
    while True:
        boxes = cdp.eval("""[...document.querySelectorAll('#net-strip .slave')].map(b =>
          [b.dataset.slave, b.dataset.alState, b.querySelector('.sl-al-state').textContent])""") or []
        if len(boxes) == n:
            seen |= {pos for pos, state, text in boxes if state == "8" and text == "Op"}
            if len(seen) == n:
                break
        if time.monotonic() > deadline:
            raise CheckFailed(f"not every slave reached Op on the page within {timeout} s (seen in Op: "
                              f"{sorted(seen) or 'none'}); the page shows: {cdp.eval(SLAVES_SHOWN)}")
        time.sleep(0.05)
    print(f"page: all {n} slaves reached Op: {cdp.eval(SLAVES_SHOWN)}")


def plot_state(cdp, slave):
    return cdp.eval(f"""(() => {{
      const c = document.querySelector('.axis[data-slave="{slave}"] canvas');
      const chart = c && Chart.getChart(c);
      if (!chart) return null;
      const pos = chart.data.datasets.find(d => d.label === 'position').data;
      return {{points: pos.length, last_t: pos.length ? pos[pos.length - 1].x : null,
               distinct: new Set(pos.map(p => p.y)).size}};
    }})()""")


def check_plot(cdp, slave, timeout):
    chart = f"Chart.getChart(document.querySelector('.axis[data-slave=\"{slave}\"] canvas'))"
    # The drives are enabled a moment after Op: wait for the plotted position to move.
    cdp.wait_for(f"""(() => {{ const ch = {chart}; if (!ch) return false;
                      const pos = ch.data.datasets.find(d => d.label === 'position').data;
                      return pos.length >= 10 && new Set(pos.map(p => p.y)).size >= 5; }})()""",
                 timeout, f"slave {slave}'s plot with 10 points and a moving position",
                 f"(() => {{ const ch = {chart}; return ch ? JSON.stringify(ch.data.datasets.map(d => d.label + ':' + d.data.length)) : 'no chart'; }})()")
    first = plot_state(cdp, slave)
    time.sleep(1.0)
    second = plot_state(cdp, slave)
    print(f"page: slave {slave} plot: {first} then, 1 s later, {second}")
    if not (second["last_t"] > first["last_t"]):
        raise CheckFailed(f"slave {slave}'s plot got no new points in 1 s ({first} -> {second})")
    return second


def measure_rate(cdp, seconds):
    n0 = cdp.eval("window.vdrivePage.updates")
    time.sleep(seconds)
    n1 = cdp.eval("window.vdrivePage.updates")
    return (n1 - n0) / seconds


def inject_fault(cdp, kind, slave, expect_alarm, timeout):
    sel = f'.axis[data-slave="{slave}"]'
    # An alarm already there (a host stall can trip a following error) would pass for the fault's.
    before = cdp.eval(f"document.querySelector('{sel} [data-role=alarm-code]').textContent.trim()")
    if before:
        raise CheckFailed(f"slave {slave} shows alarm {before} before the fault was started")
    cdp.eval("document.querySelector('.tabs button[data-tab=\"faults\"]').click()")
    cdp.wait_for(f"[...document.querySelectorAll('#fault-kind option')].some(o => o.value === {js(kind)})",
                 10, f"fault kind {kind} in #fault-kind", "[...document.querySelectorAll('#fault-kind option')].map(o => o.value).join(' ')")
    cdp.eval(f"""(() => {{
      const k = document.querySelector('#fault-kind');
      k.value = {js(kind)};
      k.dispatchEvent(new Event('change'));
      document.querySelector('#fault-slave').value = {js(str(slave))};
      document.querySelector('#fault-now').checked = true;
      document.querySelector('#fault-inject').click();
    }})()""")
    result = cdp.wait_for("(() => { const r = document.querySelector('#fault-result');"
                          " return r.textContent && (r.classList.contains('ok') ? 'ok: ' : 'err: ') + r.textContent; })()",
                          10, "an answer to the fault button")
    print(f"page: fault button: {result}")
    if not result.startswith("ok: "):
        raise CheckFailed(f"the fault was refused: {result}")
    code = cdp.wait_for(f"document.querySelector('{sel} [data-role=alarm-code]').textContent.trim()",
                        timeout, f"an alarm on slave {slave}'s axis panel",
                        f"document.querySelector('{sel} .axis-head').textContent.replace(/\\s+/g, ' ')")
    alarm = cdp.eval(f"""(() => {{
      const a = document.querySelector('{sel}');
      return {{code: a.querySelector('[data-role=alarm-code]').textContent.trim(),
               text: a.querySelector('[data-role=alarm]').textContent.replace(/\\s+/g, ' ').trim(),
               error_code: Number(a.dataset.errorCode), state: a.dataset.pds,
               visible: getComputedStyle(a.querySelector('[data-role=alarm]')).visibility === 'visible'}};
    }})()""")
    print(f"page: slave {slave} shows {alarm['text']}, CiA 402 state {alarm['state']}")
    if not alarm["visible"]:
        raise CheckFailed(f"slave {slave}'s alarm {code} is not visible")
    if alarm["error_code"] == 0:
        raise CheckFailed(f"slave {slave} shows alarm {code} with 603Fh 0")
    if expect_alarm and alarm["code"] != expect_alarm:
        raise CheckFailed(f"slave {slave} shows alarm {alarm['code']}, not {expect_alarm} as {kind} gives")
    return alarm


def write_read_only(cdp, slave, index, sub, value, expected_abort, timeout):
    cdp.eval("document.querySelector('.tabs button[data-tab=\"od\"]').click()")
    # A search first, as a user finds the object by name.
    cdp.eval(f"""(() => {{
      document.querySelector('#od-slave').value = {js(str(slave))};
      document.querySelector('#od-query').value = 'statusword';
      document.querySelector('#od-search').click();
    }})()""")
    cdp.wait_for("document.querySelectorAll('#od-list tbody tr[data-index]').length > 0", timeout,
                 "search results for 'statusword'", "document.querySelector('#od-list tbody').textContent")
    cdp.eval(f"""(() => {{
      document.querySelector('#od-result').textContent = '';
      document.querySelector('#od-index').value = {js(index)};
      document.querySelector('#od-sub').value = {js(sub)};
      document.querySelector('#od-hex').checked = false;
      document.querySelector('#od-value').value = {js(value)};
      document.querySelector('#od-write').click();
    }})()""")
    text = cdp.wait_for("document.querySelector('#od-result').textContent", timeout, "an answer to the OD write")
    refused = cdp.eval("document.querySelector('#od-result').classList.contains('err')")
    print(f"page: write {index}:{sub} = {value} on slave {slave}: {text!r}")
    if not refused or expected_abort.lower() not in text.lower():
        raise CheckFailed(f"writing {index}:{sub} was not refused with {expected_abort}: {text!r}")
    return text


def screenshot(cdp, path):
    shot = cdp.call("Page.captureScreenshot", format="png")
    with open(path, "wb") as f:
        f.write(base64.b64decode(shot["data"]))
    print(f"page: screenshot {path}")


def main():
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--url", required=True)
    ap.add_argument("--slaves", type=int, required=True, help="slaves the line has")
    ap.add_argument("--fault", default="overload", help="fault kind to start from the page")
    ap.add_argument("--fault-slave", type=int, default=1)
    ap.add_argument("--expect-alarm", help="the alarm code the fault gives on that slave's product (docs/faults.md)")
    ap.add_argument("--screenshot", help="PNG to write (default: a temporary file)")
    ap.add_argument("--result", help="JSON file for what the page showed")
    ap.add_argument("--chromium", default="/usr/bin/chromium")
    ap.add_argument("--timeout", type=float, default=60, help="seconds to wait for the line to reach Op")
    ap.add_argument("--min-rate", type=float, default=15, help="live updates per second the page must receive")
    args = ap.parse_args()

    if not (os.path.isfile(args.chromium) and os.access(args.chromium, os.X_OK)):
        print(f"SKIP: no chromium at {args.chromium}")
        return 77
    profile = tempfile.mkdtemp(prefix="vdrive-cdp-")
    proc = None
    cdp = None
    try:
        # The browser first (it takes seconds to start on a busy machine), so the page opens as
        # soon as vdrive serves it and sees the line come up.
        proc, ws_url = start_chromium(args.chromium, profile)
        wait_for_server(args.url, 30)
        cdp = Cdp(ws_url)
        cdp.call("Runtime.enable")
        cdp.call("Page.enable")
        cdp.call("Emulation.setDeviceMetricsOverride", width=1600, height=1000, deviceScaleFactor=1, mobile=False)
        cdp.call("Page.navigate", url=args.url)
        cdp.wait_for("document.readyState === 'complete' && !!window.Chart && !!window.vdrivePage", 20,
                     "the page and Chart.js loaded", "document.readyState + ' Chart=' + typeof window.Chart")

        check_slaves_op(cdp, args.slaves, args.timeout)
        plot = check_plot(cdp, args.fault_slave, 20)
        rate = measure_rate(cdp, 3.0)
        print(f"page: {rate:.1f} live updates per second")
        if rate < args.min_rate:
            raise CheckFailed(f"the page received {rate:.1f} updates per second, fewer than {args.min_rate}")
        alarm = inject_fault(cdp, args.fault, args.fault_slave, args.expect_alarm, 15)
        od = write_read_only(cdp, args.fault_slave, "6041", "0", "0", "0x06010002", 10)
        time.sleep(0.3)   # the last stream update painted
        shot = args.screenshot or os.path.join(tempfile.gettempdir(), f"vdrive-web-{os.getpid()}.png")
        screenshot(cdp, shot)
        if cdp.exceptions:
            raise CheckFailed("the page threw: " + " | ".join(map(str, cdp.exceptions[:5])))
        if args.result:
            with open(args.result, "w") as f:
                json.dump({"slaves_op": args.slaves, "plot": plot, "updates_per_second": rate, "alarm": alarm,
                           "od_refusal": od, "screenshot": shot}, f, indent=1)
        print("page: every check held")
        return 0
    except CheckFailed as e:
        print(f"FAIL: {e}")
        if cdp:
            try:
                screenshot(cdp, os.path.join(tempfile.gettempdir(), f"vdrive-web-failed-{os.getpid()}.png"))
            except Exception:  # noqa: BLE001 - the failure above is the one to report
                pass
        return 1
    finally:
        if cdp:
            cdp.close()
        if proc:
            proc.terminate()
            try:
                proc.wait(10)
            except subprocess.TimeoutExpired:
                proc.kill()
                proc.wait()
        # Chromium's helper processes may still write into the profile for a moment.
        for _ in range(20):
            shutil.rmtree(profile, ignore_errors=True)
            if not os.path.exists(profile):
                break
            time.sleep(0.1)


if __name__ == "__main__":
    sys.exit(main())
