#!/usr/bin/env python3
# SPDX-License-Identifier: MIT
"""End to end in a real browser: sbr_detect writes a CAN log over GTSDB images, the
dashboard replays it, headless Chromium (Debian's, driven by Playwright) opens the page,
and what the page shows equals what the log holds. Then fault injection: a copy of the log
with a flipped bit, a repeated frame, a lost frame (skipped counter), a message silent for
one second, a value outside its DBC range and an unknown identifier; the page shows each
error state and keeps running. What a CAN engineer checks: a message row expanded shows the
signals of its newest frame; the row's DLC and bytes are the log's last frame of that
identifier and its measured period is within 10 % of the log's; the trace filter keeps
only the frames of the identifier typed in; the stills log (its tracked-object frames say
NoObject) shows "0 tracked objects". The terminal view, run under a pseudo-terminal of 80 and of 120
columns, has no line longer than the terminal (so none is wrapped inside a number) and the
same problems list as the page, line for line. Screenshots are kept in --work (the page,
a row expanded, the trace view, the terminal at 80 and 120 columns).

The expected values are computed here from the log lines themselves (own candump parser,
own CRC, bit fields read by hand from the DBC's layout), not by the dashboard's code.

usage: e2e_browser.py --detect-tool SBR_DETECT --input GTSDB_DIR --work DIR
                      [--range 400-459] [--chromium /usr/bin/chromium]
Exit 77 (ctest: skipped) when the images or the browser are missing.
"""
import argparse
import fcntl
import html
import os
import pty
import re
import struct
import termios
import shutil
import subprocess
import sys

HERE = os.path.dirname(os.path.abspath(__file__))
DASHBOARD = os.path.dirname(HERE)
sys.path.insert(0, os.path.join(os.path.dirname(DASHBOARD), "tests", "python"))
from candump import e2e_crc, read_candump as read_log, write_candump as write_log  # noqa: E402


def bits(data, start, length):
    return (int.from_bytes(bytes(data), "little") >> start) & ((1 << length) - 1)


def set_bits(data, start, length, value):
    v = int.from_bytes(bytes(data), "little")
    v = (v & ~(((1 << length) - 1) << start)) | (value << start)
    return bytearray(v.to_bytes(8, "little"))


def protect(fid, data):
    data[0] = e2e_crc(fid, data)
    return data


def expected(frames):
    """What a consumer must show after the whole (fault-free) log."""
    status = [d for _, _, fid, d in frames if fid == 0x301]
    limit, signs, pending = None, [], []
    names_ending = {6, 32, 41, 42}  # DBC value names RestrictionEnds*
    for _, _, fid, d in frames:
        if fid != 0x300:
            continue
        slot, cls, speed, count = bits(d, 12, 4), bits(d, 16, 8), bits(d, 32, 8), bits(d, 56, 4)
        if count == 0:
            pending, signs = [], []
            continue
        if slot == 0:
            pending = []
        pending.append((cls, speed))
        if len(pending) == count:
            signs = pending
            for c, sp in signs:
                if c in names_ending:
                    limit = None
                    break
                if sp != 255:
                    limit = sp
                    break
    # the ECU's restrictions in force (SBR_Restrictions): its limit, not a reading of the signs
    restr = [d for _, _, fid, d in frames if fid == 0x302]
    bans = []
    if restr:
        r = restr[-1]
        limit = bits(r, 16, 8) or None
        bans = [name for name, bit in (("no-overtaking", 24), ("no-overtaking-trucks", 25), ("priority", 26))
                if bits(r, bit, 1)]
    last = status[-1]
    return dict(frames=len(frames), status_frames=len(status), speed_limit=limit, restrictions=bans,
                restriction_frames=len(restr),
                sign_count=len(signs), frame_counter=bits(last, 16, 16),
                processing_ms=bits(last, 32, 16) * 0.1,
                processing_mean=sum(bits(d, 32, 16) for d in status) * 0.1 / len(status),
                # an image is an overload when its processing took longer than the status
                # message's 100 ms cycle (GenMsgCycleTime) or the ECU dropped results
                overload=sum(1 for d in status if bits(d, 12, 1) or bits(d, 32, 16) * 0.1 > 100),
                error=sum(bits(d, 13, 1) for d in status),
                capacity=sum(bits(d, 14, 1) for d in status))


def inject_faults(frames):
    """The fault log and the count of each fault per message."""
    images = sorted({t for t, *_ in frames})
    at = lambda k, fid: [i for i, f in enumerate(frames) if f[0] == images[k] and f[2] == fid]
    out = [list(f[:3]) + [bytearray(f[3])] for f in frames]
    drop = set()
    # 1. a flipped bit in the status frame of image 10 -> CRC error
    i = at(10, 0x301)[0]
    out[i][3][4] ^= 0x08
    # 2. image 20's detection frames lost -> the next detection frame: skipped counter
    drop.update(at(20, 0x310))
    # 3. tracked objects silent for images 30..39 (1 s, limit 3 x 100 ms) -> one timeout;
    #    the ECU did not send them, so its later counters continue without a gap
    silent = [i for k in range(30, 40) for i in at(k, 0x320)]
    drop.update(silent)
    for k in range(40, len(images)):
        for i in at(k, 0x320):
            c = (bits(out[i][3], 8, 4) - len(silent)) % 15
            out[i][3] = protect(0x320, set_bits(out[i][3], 8, 4, c))
    # 5. image 50's first detection frame: confidence raw 63 (126 %, range 0..100), valid E2E
    i = at(50, 0x310)[0]
    out[i][3] = protect(0x310, set_bits(out[i][3], 18, 6, 63))
    result = [f for k, f in enumerate(out) if k not in drop]
    # 4. image 25's confirmed-sign frame sent twice -> repeated counter
    j = next(k for k, f in enumerate(result) if f[0] == images[25] and f[2] == 0x300)
    result.insert(j + 1, [result[j][0], result[j][1], 0x300, bytearray(result[j][3])])
    # 6. an identifier the DBC does not know
    result.insert(j + 2, [result[j][0], result[j][1], 0x7FF, bytearray(8)])
    # a frame lost to a CRC error makes the next one of its message "skipped", as in E2E
    want = {"SBR_EcuStatus": dict(crc=1, skipped=1), "SBR_Detection": dict(skipped=1, out_of_range=1),
            "SBR_TrackedObject": dict(timeouts=1), "SBR_ConfirmedSign": dict(repeated=1)}
    return result, want


def log_period_ms(frames, fid, cycle_ms=100.0):
    """The log's own cycle period of one identifier: mean time between the first frames of
    consecutive cycles (frames less than a quarter cycle apart are one cycle)."""
    starts, last = [], None
    for t, _, f, _ in frames:
        if f != fid:
            continue
        if last is None or (t - last) / 1000.0 >= 0.25 * cycle_ms:  # times in microseconds
            starts.append(t)
        last = t
    return (starts[-1] - starts[0]) / 1000.0 / (len(starts) - 1)


def terminal_screen(python, log, cols, rows=60):
    """The dashboard's --terminal --once screen under a pseudo-terminal of cols columns."""
    master, slave = pty.openpty()
    fcntl.ioctl(slave, termios.TIOCSWINSZ, struct.pack("HHHH", rows, cols, 0, 0))
    env = dict(os.environ)
    env.pop("COLUMNS", None)
    env.pop("LINES", None)
    proc = subprocess.Popen([os.path.join(os.path.dirname(python), "sbr-dashboard"), "--log", log, "--fast",
                             "--terminal", "--once"], stdin=slave, stdout=slave, stderr=slave, env=env)
    os.close(slave)
    out = b""
    while True:
        try:
            chunk = os.read(master, 65536)
        except OSError:
            break
        if not chunk:
            break
        out += chunk
    os.close(master)
    assert proc.wait(30) == 0, proc.returncode
    return out.decode().replace("\r\n", "\n")


def terminal_problems(screen):
    """The problems section of a terminal screen, continuation lines joined."""
    lines = screen.split("\n")
    start = lines.index("recent problems:") + 1
    out = []
    for ln in lines[start:]:
        if ln.startswith("      ") and out:
            out[-1] += " " + ln.strip()
        elif ln.startswith("  "):
            out.append(ln.strip())
    return out


def shot_text(browser, text, path, cols):
    """A screenshot of a terminal screen, drawn in a monospace page cols characters wide."""
    page = browser.new_page(viewport={"width": cols * 9 + 40, "height": 400})
    page.set_content("<body style='margin:0;background:#000'><pre style='margin:12px;color:#ddd;"
                     f"font:15px monospace;width:{cols}ch'>{html.escape(text)}</pre></body>")
    page.screenshot(path=path, full_page=True)
    page.close()
    print(f"screenshot: {path}")


def check_engineer_views(page, frames, work):
    """A row expanded (signals, DLC, bytes, period), then the trace filter."""
    fid, name = 0x301, "SBR_EcuStatus"
    last = [d for _, _, f, d in frames if f == fid][-1]
    row = page.locator(f'#messages tr.msg[data-msg="{name}"]')
    row.click()
    page.wait_for_selector(f'#messages tr.signals[data-for="{name}"]')
    dlc = row.locator("td.dlc").inner_text()
    data = row.locator("td.bytes").inner_text()
    period = float(row.locator("td.period").inner_text().split()[0])
    want_period = log_period_ms(frames, fid)
    assert dlc == str(len(last)), (dlc, len(last))
    assert data == bytes(last).hex(" ").upper(), (data, bytes(last).hex(" "))
    assert abs(period - want_period) <= 0.1 * want_period, (period, want_period)
    sig = page.locator(f'#messages tr.signals[data-for="{name}"] table.sig tbody tr')
    values = {r.locator("td.sig-name").inner_text(): r.locator("td.sig-value").inner_text() for r in sig.all()}
    assert values["SBR_Status_FrameCounter"] == str(bits(last, 16, 16)), values
    assert values["SBR_Status_ProcessingTime"].endswith(" ms"), values
    print(f"message detail: {name} DLC {dlc}, bytes {data}, period {period} ms (log {want_period:.1f} ms), "
          f"{len(values)} signals with units")
    page.screenshot(path=os.path.join(work, "dashboard_row_expanded.png"), full_page=True)
    print(f"screenshot: {os.path.join(work, 'dashboard_row_expanded.png')}")
    page.fill("#trace-filter", "0x310")
    page.wait_for_timeout(200)
    ids = page.locator("#trace tbody tr").evaluate_all("rs => rs.map(r => r.dataset.id)")
    shown = int(page.locator("#trace-count").inner_text())
    want = sum(1 for _, _, f, _ in frames[-shown:] if f == 0x310)
    assert ids and set(ids) == {"0x310"} and len(ids) == want, (len(ids), want, set(ids))
    page.fill("#trace-filter", "SBR_EcuStatus")
    page.wait_for_timeout(200)
    ids = page.locator("#trace tbody tr").evaluate_all("rs => rs.map(r => r.dataset.id)")
    assert ids and set(ids) == {"0x301"}, set(ids)
    page.locator("#trace-panel").scroll_into_view_if_needed()
    page.locator("#trace-panel").screenshot(path=os.path.join(work, "dashboard_trace.png"))
    print(f"trace filter: 0x310 -> {want} of the last {shown} frames; screenshot "
          f"{os.path.join(work, 'dashboard_trace.png')}")
    page.fill("#trace-filter", "")
    # a log of stills: the tracked-object frames arrive, each saying NoObject
    assert page.locator("#obj-text").inner_text().strip() == "0 tracked objects"


class Dashboard:
    def __init__(self, python, log, rate, work, name):
        self.out = open(os.path.join(work, f"{name}.out"), "w+")
        self.proc = subprocess.Popen(
            # the console script the package installs beside the interpreter (pyproject.toml)
            [os.path.join(os.path.dirname(python), "sbr-dashboard"), "--log", log, "--rate", str(rate),
             "--port", "0", "--wait-client"], stdout=subprocess.PIPE, stderr=self.out, text=True)
        line = self.proc.stdout.readline()
        m = re.search(r"open (http://\S+)", line)
        assert m, f"dashboard did not say where to open: {line!r}"
        self.url = m.group(1)
        print(f"dashboard: {line.strip()}")

    def stop(self):
        self.proc.terminate()
        try:
            self.proc.wait(10)
        except subprocess.TimeoutExpired:
            self.proc.kill()
        assert self.proc.returncode in (0, -15), self.proc.returncode


def page_values(page):
    t = lambda sel: page.locator(sel).inner_text().strip()
    rows = {}
    for r in page.locator("#messages tbody tr").all():
        name = r.get_attribute("data-msg")
        rows[name] = {c: int(r.locator(f"td.{c}").inner_text()) for c in
                      ("received", "valid", "crc", "repeated", "skipped", "bad_counter", "length",
                       "out_of_range", "timeouts")}
        rows[name]["state"] = r.locator("td.state").inner_text()
    return dict(speed_limit=t("#speed-limit"), sign_count=int(t("#sign-count")),
                restrictions=[e.get_attribute("id")[len("restr-"):] for e in page.locator("#restr-icons .restr").all()],
                sign_icons=page.locator("#signs .sign").count(), frames=int(t("#h-frames")),
                status_frames=int(t("#h-status-frames")), frame_counter=t("#h-frame-counter"),
                proc=t("#h-proc"), proc_mean=t("#h-proc-mean"), fps=t("#h-fps"),
                overload=int(t("#h-overload")), error=int(t("#h-error")),
                capacity=int(t("#h-capacity")), e2e=int(t("#t-e2e")),
                timeouts=int(t("#t-timeouts")), range=int(t("#t-range")),
                unknown=int(t("#h-unknown")), rows=rows, source_state=t("#source-state"),
                link=t("#link-state"), updates=int(page.evaluate("document.body.dataset.updates")),
                events=[e.strip() for e in page.locator("#events li").all_inner_texts()])


def open_page(browser, url, shot):
    page = browser.new_page(viewport={"width": 1400, "height": 1000})
    page.goto(url)
    page.wait_for_selector('body[data-ended="1"]', timeout=120000)
    page.wait_for_timeout(300)  # the last event has been rendered
    v = page_values(page)
    page.screenshot(path=shot, full_page=True)
    print(f"screenshot: {shot}")
    return page, v


def main():
    ap = argparse.ArgumentParser()
    ap.add_argument("--detect-tool", required=True)
    ap.add_argument("--input", required=True)
    ap.add_argument("--work", required=True)
    ap.add_argument("--range", default="400-459")
    ap.add_argument("--rate", type=float, default=4.0)
    ap.add_argument("--chromium", default=shutil.which("chromium") or "/usr/bin/chromium")
    a = ap.parse_args()
    if not os.path.isdir(a.input):
        print(f"SKIP: no image folder {a.input}")
        return 77
    if not os.path.exists(a.chromium):
        print(f"SKIP: no Chromium at {a.chromium}")
        return 77
    from playwright.sync_api import sync_playwright

    os.makedirs(a.work, exist_ok=True)
    log = os.path.join(a.work, "sbr_can.log")
    subprocess.run([a.detect_tool, "--input", a.input, "--range", a.range, "--quiet",
                    "--detections", os.path.join(a.work, "detections.txt"), "--canlog", log],
                   check=True)
    frames = read_log(log)
    want = expected(frames)
    assert want["speed_limit"] is not None, "the log should hold a speed limit"
    print(f"log: {want['frames']} frames, {want['status_frames']} images, speed limit "
          f"{want['speed_limit']} km/h, {want['sign_count']} confirmed signs listed last")

    fault_log = os.path.join(a.work, "sbr_can_faults.log")
    faulted, fault_want = inject_faults(frames)
    write_log(fault_log, faulted)

    with sync_playwright() as pw:
        browser = pw.chromium.launch(executable_path=a.chromium, headless=True,
                                     args=["--no-sandbox", "--disable-gpu"])
        # 1. the clean log
        dash = Dashboard(sys.executable, log, a.rate, a.work, "dashboard_clean")
        try:
            page, v = open_page(browser, dash.url, os.path.join(a.work, "dashboard_e2e.png"))
            # what the driver is shown: the limit in force and the bans, as a cluster draws them
            page.locator("#limit-panel").screenshot(path=os.path.join(a.work, "dashboard_restrictions.png"))
            print(f"screenshot: {os.path.join(a.work, 'dashboard_restrictions.png')}")
            check_engineer_views(page, frames, a.work)
        finally:
            dash.stop()
        print("page (clean log):", {k: v[k] for k in v if k not in ("rows", "events")})
        print("expected from the log:", want)
        assert want["restriction_frames"] == want["status_frames"], "one SBR_Restrictions frame per image"
        assert v["speed_limit"] == f"{want['speed_limit']} km/h", (v["speed_limit"], want)
        assert v["restrictions"] == want["restrictions"], (v["restrictions"], want["restrictions"])
        assert v["sign_count"] == v["sign_icons"] == want["sign_count"]
        assert v["frames"] == want["frames"] and v["status_frames"] == want["status_frames"]
        assert v["frame_counter"] == str(want["frame_counter"])
        # shown with one decimal: equal within half of it (the page and this test sum the
        # times in different float order, so a mean on a .x5 boundary may round either way)
        assert abs(float(v["proc"]) - want["processing_ms"]) <= 0.05 + 1e-9, v["proc"]
        assert abs(float(v["proc_mean"]) - want["processing_mean"]) <= 0.05 + 1e-9, v["proc_mean"]
        assert abs(float(v["fps"]) - 10.0) < 0.05, v["fps"]  # images 100 ms apart in the log
        assert (v["overload"], v["error"], v["capacity"]) == \
            (want["overload"], want["error"], want["capacity"])
        assert v["e2e"] == v["timeouts"] == v["range"] == v["unknown"] == 0, v
        assert all(r["state"] == "ok" and r["received"] == r["valid"] for r in v["rows"].values())
        assert v["source_state"] == "source ended" and v["link"] == "live"
        assert v["updates"] >= 2, "the page should have been updated live"
        print(f"clean log: the page equals the log (updated {v['updates']} times while it played)")

        # 2. the fault log
        dash = Dashboard(sys.executable, fault_log, a.rate, a.work, "dashboard_faults")
        try:
            page, v = open_page(browser, dash.url, os.path.join(a.work, "dashboard_faults.png"))
            for name, counts in fault_want.items():
                row = v["rows"][name]
                for key in ("crc", "repeated", "skipped", "bad_counter", "length", "out_of_range",
                            "timeouts"):
                    assert row[key] == counts.get(key, 0), (name, key, row)
                print(f"fault caught: {name} {counts} (row state now '{row['state']}')")
            assert v["unknown"] == 1 and v["e2e"] == 4 and v["timeouts"] == 1 and v["range"] == 1
            assert v["frames"] == len(faulted), "every frame after the faults was processed"
            assert v["status_frames"] == want["status_frames"] - 1  # the corrupted one
            kinds = " | ".join(v["events"])
            for text in ("CRC mismatch", "alive counter repeated", "alive counter skipped",
                         "no frame for more than 300 ms", "SBR_Det_Confidence=126", "id 0x7FF",
                         "recovered"):
                assert text in kinds, (text, kinds)
            assert page.locator("#t-e2e.nonzero").count() == 1
            assert page.locator("#t-timeouts.nonzero").count() == 1
            assert page.locator("#t-range.nonzero").count() == 1
            assert v["link"] == "live", "the page keeps running"
        finally:
            dash.stop()
        # 3. the terminal: the page's problems, lines that fit, at 80 and 120 columns
        for cols in (80, 120):
            screen = terminal_screen(sys.executable, fault_log, cols)
            longest = max(len(ln) for ln in screen.split("\n"))
            assert longest <= cols, (cols, longest)
            problems = terminal_problems(screen)
            assert problems == v["events"], (cols, problems, v["events"])
            with open(os.path.join(a.work, f"terminal_{cols}.txt"), "w") as f:
                f.write(screen)
            shot_text(browser, screen, os.path.join(a.work, f"terminal_{cols}.png"), cols)
            print(f"terminal at {cols} columns: longest line {longest}, the page's {len(problems)} problems")
        browser.close()
    print("dashboard end-to-end: OK")
    return 0


if __name__ == "__main__":
    sys.exit(main())
