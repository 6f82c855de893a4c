"""Terminal mode: one screen, redrawn in place (ANSI home + clear), for machines without
a browser."""

HOME_CLEAR = "\x1b[H\x1b[J"


def render(s, width=78):
    h = s["health"]
    st = h["status"] or {}
    lines = []
    lines.append(f"sbr dashboard - {s['source']}" + ("  [source ended]" if s["source_ended"] else ""))
    lines.append("=" * width)
    limit = s["speed_limit"]
    lines.append(f"SPEED LIMIT: {limit if limit is not None else '--'}" +
                 (" km/h" if limit is not None else ""))
    if s["signs"]:
        signs = ", ".join(f"{x['class_name'] or x['class_id']} {x['confidence']:.0f}% "
                          f"(age {x['age']})" for x in s["signs"])
    else:
        signs = "none"
    lines.append(f"confirmed signs: {signs}")
    dets = ", ".join(f"{d['class_name'] or d['class_id']} {d['confidence']:.0f}% @"
                     f"({d['cx']:.0f},{d['cy']:.0f})" for d in s["detections"]) or "none"
    lines.append(f"detections (last image): {dets}")
    objs = ", ".join(f"#{o['track']} ({o['x']:.0f},{o['y']:.0f})" for o in s["objects"]) or "none"
    lines.append(f"tracked objects: {objs}")
    lines.append("-" * width)
    fmt = lambda v: "--" if v is None else f"{v:.1f}"  # noqa: E731
    lines.append(f"ECU: {h['fps']:.1f} images/s  processing {fmt(h['processing_ms'])} ms "
                 f"(mean {fmt(h['processing_ms_mean'])})  "
                 f"frame counter {st.get('FrameCounter', '--')}  regions {st.get('RegionCount', '--')}")
    fc = h["flag_counts"]
    lines.append(f"flags: overload {fc['overload']}  error {fc['error']}  capacity {fc['capacity']}   "
                 f"frames {s['frames']}  unknown {s['unknown']}  source time {s['source_time']:.1f} s")
    lines.append("-" * width)
    lines.append(f"{'message':<20}{'state':<12}{'rx':>7}{'crc':>5}{'rep':>5}{'skip':>5}"
                 f"{'ctr':>5}{'len':>5}{'range':>6}{'tmo':>5}")
    for m in s["messages"]:
        lines.append(f"{m['name']:<20}{m['state']:<12}{m['received']:>7}{m['crc']:>5}"
                     f"{m['repeated']:>5}{m['skipped']:>5}{m['bad_counter']:>5}{m['length']:>5}"
                     f"{m['out_of_range']:>6}{m['timeouts']:>5}")
    lines.append("-" * width)
    lines.append("recent problems:")
    for e in [e for e in s["events"] if e["kind"] != "source"][:6]:
        lines.append(f"  {e['t']:8.2f} s {e['message']:<18} {e['kind']:<9} {e['detail']}"[:width])
    return "\n".join(lines) + "\n"
