# SPDX-License-Identifier: MIT
"""Terminal mode: one screen, redrawn in place (ANSI home + clear), for machines without
a browser.

The screen is laid out to the terminal's width (render(s, width); the console uses the
terminal's own size): no line is longer than the width, so the terminal never wraps one,
and text that does not fit goes on to the next line at a space, never inside a number or
a name. The message tables have fixed columns that fit 80 columns; the name column is as
wide as the longest message name. The problems are the page's list, line for line
(monitor.event_text), a continued problem indented by six spaces."""
import shutil

HOME_CLEAR = "\x1b[H\x1b[J"
MIN_WIDTH = 40
CONTINUED = "      "


def terminal_width(default=80):
    return max(MIN_WIDTH, shutil.get_terminal_size((default, 24)).columns)


def flow(pieces, width, first="", indent="  ", sep=" "):
    """The pieces in lines of at most `width` columns: `first` starts the first line,
    `indent` the others, `sep` goes between pieces on a line; a line breaks only between
    pieces (a piece longer than a whole line is cut: the only case one is split)."""
    lines, cur, fresh = [], first, True
    for p in pieces:
        piece = p if fresh else sep + p
        if len(cur) + len(piece) > width and not fresh:
            lines.append(cur.rstrip())
            cur, piece = indent, p
        cur += piece
        fresh = False
        while len(cur) > width:
            lines.append(cur[:width])
            cur = indent + cur[width:]
    lines.append(cur.rstrip())
    return lines


def wrap(text, width, indent="", first=""):
    """Text broken at spaces into lines of at most `width` columns."""
    return flow([w for w in text.split(" ") if w], width, first, indent)


def items(label, parts, width):
    """'label: a, b, c', broken between items only."""
    parts = parts or ["none"]
    return flow([p + ("," if i + 1 < len(parts) else "") for i, p in enumerate(parts)], width, f"{label}: ")


def _fmt(v, digits=1):
    return "--" if v is None else f"{v:.{digits}f}"


def _table(rows, cols, name_w):
    """Rows of a fixed-width table: cols = [(title, key or function, width, align)]."""
    def cell(c, r):
        title, key, w, align = c
        v = r if r is None else (key(r) if callable(key) else r[key])
        text = title if r is None else str(v)
        w = name_w if w == 0 else w
        return f"{text:<{w}}" if align == "<" else f"{text:>{w}}"
    return ["".join(cell(c, None) for c in cols).rstrip()] + \
           ["".join(cell(c, r) for c in cols).rstrip() for r in rows]


def render(s, width=78):
    width = max(MIN_WIDTH, width)
    h = s["health"]
    st = h["status"] or {}
    out = []
    out += wrap(f"sbr dashboard - {s['source']}" + ("  [source ended]" if s["source_ended"] else ""), width)
    out.append("=" * width)
    limit = s["speed_limit"]
    out.append(f"SPEED LIMIT: {limit} km/h" if limit is not None else "SPEED LIMIT: --")
    out += items("confirmed signs", [f"{x['class_name'] or x['class_id']} {x['confidence']:.0f} % "
                                     f"(age {x['age']} frames)" for x in s["signs"]], width)
    out += items("detections (last image)", [f"{d['class_name'] or d['class_id']} {d['confidence']:.0f} % "
                                             f"at ({d['cx']:.0f} px, {d['cy']:.0f} px)" for d in s["detections"]],
                 width)
    if s.get("tracker_seen", True):
        out += items("tracked objects", [f"#{o['track']} at ({o['x']:.0f} px, {o['y']:.0f} px) moving "
                                         f"({o['vx']:.0f} px/s, {o['vy']:.0f} px/s) {o['certainty']:.0f} %"
                                         for o in s["objects"]], width)
    else:
        out += wrap("tracked objects: no SBR_TrackedObject frame received so far", width, "  ")
    out.append("-" * width)
    cycle = h.get("cycle_ms")
    ecu = [f"{h['fps']:.1f} images/s",
           f"processing {_fmt(h['processing_ms'])} ms (mean {_fmt(h['processing_ms_mean'])} ms"
           + (f", cycle {cycle} ms)" if cycle else ")"),
           f"frame counter {st.get('FrameCounter', '--')}", f"regions {st.get('RegionCount', '--')}"]
    if h.get("overload_now"):
        ecu.insert(0, "OVERLOAD")
    out += items("ECU", ecu, width)
    fc = h["flag_counts"]
    out += items("flags (images)", [f"overload {fc['overload']} (late {fc.get('late', 0)}, dropped "
                                    f"{fc.get('dropped', 0)})", f"error {fc['error']}", f"capacity {fc['capacity']}"],
                 width)
    out += items("bus", [f"frames {s['frames']}", f"unknown {s['unknown']}", f"lines skipped {s['skipped_lines']}",
                         f"source time {s['source_time']:.1f} s"], width)
    out.append("-" * width)
    msgs = s["messages"]
    name_w = max([len("message")] + [len(m["name"]) for m in msgs]) + 2
    out += _table(msgs, [("message", "name", 0, "<"), ("state", "state", 12, "<"), ("rx", "received", 7, ">"),
                         ("crc", "crc", 5, ">"), ("rep", "repeated", 5, ">"), ("skip", "skipped", 5, ">"),
                         ("ctr", "bad_counter", 5, ">"), ("len", "length", 5, ">"),
                         ("range", "out_of_range", 6, ">"), ("tmo", "timeouts", 5, ">")], name_w)
    out.append("")
    out += _table(msgs, [("message", "name", 0, "<"), ("id", "id", 6, "<"),
                         ("dlc", lambda m: "--" if m["dlc"] is None else m["dlc"], 4, ">"),
                         ("period", lambda m: _fmt(m["period_ms"]), 8, ">"),
                         ("jitter", lambda m: _fmt(m["jitter_ms"]), 8, ">"),
                         ("cycle", "cycle_ms", 6, ">"), ("  last bytes", lambda m: "  " + (m["data"] or "--"), 0, "<")],
                  name_w)
    out.append("  (period, jitter: measured ms; cycle: the DBC's GenMsgCycleTime)")
    out.append("-" * width)
    out.append("recent problems:")
    for text in s.get("problems", []) or ["none"]:
        out += wrap(text, width, CONTINUED, "  ")
    # a table row wider than the screen (very long names) is cut, never wrapped by the terminal
    return "\n".join(line[:width] for line in out) + "\n"
