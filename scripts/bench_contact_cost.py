#!/usr/bin/python3
"""Cost of contact against the same bodies without it (a benchmark, not a test).

Runs inputs/squeeze_three_bodies_2d.yaml (a cylinder squeezed between two blocks,
three deformable bodies, about 27k dofs, two contact pairs) as it is, and a copy
without its contact pairs where the cylinder is held by a constraint instead
(u_y = 0 on its lower arc): the same bodies, dofs and increments. For each run it
reports the wall time, the peak memory (/usr/bin/time -v "Maximum resident set
size" of the child), Newton iterations and the /timings of the results file, then
the ratios contact / no contact. The issue's target: within 6x the time and 2x the
memory. Each case runs --repeat times; the fastest run is reported (the machine is
shared; CPU time = user + system of the child is
less sensitive to other processes than wall time). Several executables (e.g. before and after a change) may be given.

    /usr/bin/python3 scripts/bench_contact_cost.py --exe build/bin/igacontact [--exe old/igacontact] [--repeat 3]
"""
import argparse, json, os, re, subprocess, sys, tempfile, time

import h5py
import yaml

ROOT = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))
DECK = os.path.join(ROOT, "inputs", "squeeze_three_bodies_2d.yaml")


def decks(folder):
    with open(DECK) as f:
        deck = yaml.safe_load(f)
    with_contact = os.path.join(folder, "with_contact.yaml")
    with open(with_contact, "w") as f:
        yaml.safe_dump(deck, f)
    deck = dict(deck)
    deck.pop("contact")
    deck["constraints"] = deck["constraints"] + [{"body": "cylinder", "side": "v0", "fix": ["y"]}]
    without = os.path.join(folder, "without_contact.yaml")
    with open(without, "w") as f:
        yaml.safe_dump(deck, f)
    return [("with contact", with_contact), ("without contact", without)]


def run(exe, deck, out):
    cmd = ["/usr/bin/time", "-v", exe, deck, "-o", out, "-q", "--summary", "json"]
    start = time.perf_counter()
    p = subprocess.run(cmd, capture_output=True, text=True)
    wall = time.perf_counter() - start
    if p.returncode != 0:
        raise RuntimeError(f"{' '.join(cmd)} failed ({p.returncode}): {p.stderr[-600:]}")
    rss_kb = int(re.search(r"Maximum resident set size \(kbytes\): (\d+)", p.stderr).group(1))
    cpu = sum(float(re.search(rf"{k} time \(seconds\): ([0-9.]+)", p.stderr).group(1)) for k in ("User", "System"))
    summary = json.loads(p.stdout.strip().splitlines()[-1])
    with h5py.File(out, "r") as f:
        timings = {k: float(v) for k, v in f["timings"].attrs.items()}
        counters = {k: int(v) for k, v in f["counters"].attrs.items()} if "counters" in f else {}
    os.remove(out)
    return {"wall": wall, "cpu": cpu, "rss_mb": rss_kb / 1024.0, "status": summary.get("status"), "timings": timings,
            "counters": counters}


def main():
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("--exe", action="append", required=True, help="igacontact executable (repeatable)")
    ap.add_argument("--repeat", type=int, default=1)
    args = ap.parse_args()
    rows = []
    with tempfile.TemporaryDirectory() as folder:
        for exe in args.exe:
            results = {}
            for name, deck in decks(folder):
                best = None
                for _ in range(args.repeat):
                    r = run(os.path.abspath(exe), deck, os.path.join(folder, "out.h5"))
                    if r["status"] != "completed":
                        sys.exit(f"{exe} {name}: status {r['status']}")
                    best = r if best is None or r["wall"] < best["wall"] else best
                results[name] = best
            rows.append((exe, results))
    print("| executable | case | dofs | Newton it. | wall s | CPU s | peak MB | linear_solve s | contact s |")
    print("|---|---|---|---|---|---|---|---|---|")
    for exe, results in rows:
        for name, r in results.items():
            c, t = r["counters"], r["timings"]
            print(f"| {exe} | {name} | {c.get('dofs', '?')} | {c.get('total_newton_iterations', '?')} | "
                  f"{r['wall']:.2f} | {r['cpu']:.2f} | {r['rss_mb']:.0f} | {t.get('linear_solve', 0):.2f} | {t.get('contact', 0):.2f} |")
    print()
    print("| executable | wall time ratio (target <= 6) | CPU time ratio | memory ratio (target <= 2) |")
    print("|---|---|---|---|")
    for exe, results in rows:
        w, wo = results["with contact"], results["without contact"]
        print(f"| {exe} | {w['wall'] / wo['wall']:.2f} | {w['cpu'] / wo['cpu']:.2f} | {w['rss_mb'] / wo['rss_mb']:.2f} |")


if __name__ == "__main__":
    main()
