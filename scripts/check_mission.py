#!/usr/bin/env python3
"""Checks a mission written by `skyroute plan` with pymavlink, a real consumer of the formats.

    python3 scripts/check_mission.py ROUTE.waypoints ROUTE.plan

Loads the QGC WPL 110 file with pymavlink's `MAVWPLoader`, turns the QGroundControl plan's
`SimpleItem`s into `MAVLink_mission_item_int_message`s (latitude and longitude as integers in
1e-7 degrees, as MISSION_ITEM_INT carries them), and checks that both are the same mission:
the WPL file's item 0 is the plan's `plannedHomePosition`, then the same count of items with the
same command, frame, params 1-4, latitude and longitude within 1e-7 degrees and altitude.
Prints one line with the figures and exits 0, or prints what differs and exits 1; exits 2 when
pymavlink cannot be imported (the caller decides whether that is a skip).
"""

import json
import sys

try:
    from pymavlink import mavwp
    from pymavlink.dialects.v20 import common as mavlink2
except ImportError as e:  # pragma: no cover - the caller reports the skip
    print(f"pymavlink cannot be imported: {e}")
    sys.exit(2)

TOLERANCE_DEG = 1e-7


def plan_items(plan):
    """The plan's mission items as MAVLink MISSION_ITEM_INT messages, seq from 1."""
    out = []
    for seq, item in enumerate(plan["mission"]["items"], start=1):
        if item.get("type") != "SimpleItem":
            raise ValueError(f"mission.items[{seq - 1}].type: {item.get('type')!r}")
        p = [0.0 if v is None else float(v) for v in item["params"]]
        out.append(
            mavlink2.MAVLink_mission_item_int_message(
                target_system=1,
                target_component=0,
                seq=seq,
                frame=int(item["frame"]),
                command=int(item["command"]),
                current=0,
                autocontinue=int(bool(item["autoContinue"])),
                param1=p[0],
                param2=p[1],
                param3=p[2],
                param4=p[3],
                x=int(round(p[4] * 1e7)),
                y=int(round(p[5] * 1e7)),
                z=p[6],
                mission_type=0,
            )
        )
    return out


def compare(wpl, plan):
    """What differs between the WPL loader's items and the plan file (empty when nothing)."""
    problems = []
    home = plan["mission"]["plannedHomePosition"]
    w0 = wpl.wp(0)
    if abs(w0.x - home[0]) > TOLERANCE_DEG or abs(w0.y - home[1]) > TOLERANCE_DEG:
        problems.append(f"home: WPL ({w0.x}, {w0.y}) vs plan {home[:2]}")
    items = plan_items(plan)
    if wpl.count() != len(items) + 1:
        problems.append(f"count: WPL {wpl.count()} items (home included), plan {len(items)}")
        return problems
    for it in items:
        w = wpl.wp(it.seq)
        fields = [
            ("command", w.command, it.command),
            ("frame", w.frame, it.frame),
            ("autocontinue", w.autocontinue, it.autocontinue),
            ("param1", w.param1, it.param1),
            ("param2", w.param2, it.param2),
            ("param3", w.param3, it.param3),
            ("param4", w.param4, it.param4),
            ("altitude", w.z, it.z),
        ]
        for name, a, b in fields:
            if abs(a - b) > 1e-6:
                problems.append(f"item {it.seq} {name}: WPL {a}, plan {b}")
        for name, a, b in (("latitude", w.x, it.x), ("longitude", w.y, it.y)):
            if abs(a - b * 1e-7) > TOLERANCE_DEG:
                problems.append(f"item {it.seq} {name}: WPL {a}, plan {b * 1e-7}")
    return problems


def main(argv):
    if len(argv) != 3:
        print(__doc__)
        return 2
    wpl = mavwp.MAVWPLoader()
    n = wpl.load(argv[1])
    with open(argv[2], encoding="utf-8") as f:
        plan = json.load(f)
    problems = compare(wpl, plan)
    if problems:
        for p in problems[:20]:
            print(p)
        return 1
    worst = max(
        max(abs(wpl.wp(it.seq).x - it.x * 1e-7), abs(wpl.wp(it.seq).y - it.y * 1e-7))
        for it in plan_items(plan)
    )
    commands = sorted({wpl.wp(i).command for i in range(n)})
    print(
        f"same mission: {n} WPL items (home + {n - 1}), commands {commands}, "
        f"largest lat/lon difference {worst:.2e} deg"
    )
    return 0


if __name__ == "__main__":
    sys.exit(main(sys.argv))
