#!/usr/bin/python3
"""Cost of contact against the same bodies without it (a benchmark, not a test).

Cases (--case, repeatable; default all):
  squeeze  inputs/squeeze_three_bodies_2d.yaml: a cylinder squeezed between two
           blocks (three deformable bodies, ~27k dofs, two contact pairs), against
           a copy without contact where the cylinder's lower arc is held (u_y = 0).
           Issue 10 target: within 6x the time and 2x the memory.
  sphere   inputs/hertz_sphere_plane_3d.yaml: the 3D Hertz sphere octant on a
           rigid plane (~32k dofs), against an elastic run of the same mesh and
           load with the contact face held by a roller (u_z = 0).
           Issue 10 target: within 3x the time.
  spheres  inputs/hertz_two_spheres_3d.yaml: two deformable sphere octants
           (two-half-pass), against the same bodies with the lower one's contact
           face held by a roller and the upper one's too (no contact).
For every run: wall time, peak memory (/usr/bin/time -v "Maximum resident set
size" of the child), Newton iterations and the /timings of the results file, the
share of projection + search in the run (issue 10 target: <= 15 % of a 3D run),
then the ratios contact / no contact. Each case runs --repeat times; the fastest
run is reported (the machine may be shared; CPU time = user + system of the child
is less sensitive to other processes than wall time). Several executables (e.g.
before and after a change) may be given.

    /usr/bin/python3 scripts/bench_contact_cost.py --exe build/bin/igacontact [--case sphere] [--repeat 3]
"""
import argparse, json, os, re, subprocess, sys, tempfile, time

import h5py
import yaml

ROOT = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))


def squeeze(deck):
    deck.pop("contact")
    deck["constraints"] = deck["constraints"] + [{"body": "cylinder", "side": "v0", "fix": ["y"]}]


def sphere(deck):
    deck.pop("contact")
    deck["bodies"] = [b for b in deck["bodies"] if b["name"] != "floor"]
    deck["output"].pop("reference", None)
    deck["constraints"] = deck["constraints"] + [{"body": "ball", "side": "v0", "fix": ["z"]}]


def spheres(deck):
    deck.pop("contact")
    deck["output"].pop("reference", None)
    deck["constraints"] = deck["constraints"] + [{"body": "lower", "side": "v0", "fix": ["z"]},
                                                 {"body": "upper", "side": "v0", "fix": ["z"]}]


# name: (deck, how to make the run without contact, time target, memory target)
CASES = {
    "squeeze": ("squeeze_three_bodies_2d.yaml", squeeze, 6.0, 2.0),
    "sphere": ("hertz_sphere_plane_3d.yaml", sphere, 3.0, None),
    "spheres": ("hertz_two_spheres_3d.yaml", spheres, None, None),
}


def decks(folder, case):
    name, without_contact, _, _ = CASES[case]
    with open(os.path.join(ROOT, "inputs", name)) as f:
        deck = yaml.safe_load(f)
    with_contact = os.path.join(folder, f"{case}_with_contact.yaml")
    with open(with_contact, "w") as f:
        yaml.safe_dump(deck, f)
    without_contact(deck)
    without = os.path.join(folder, f"{case}_without_contact.yaml")
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
    ap.add_argument("--case", action="append", choices=sorted(CASES), help="case (repeatable; default all)")
    ap.add_argument("--repeat", type=int, default=1)
    args = ap.parse_args()
    rows = []
    with tempfile.TemporaryDirectory() as folder:
        for case in args.case or list(CASES):
            for exe in args.exe:
                results = {}
                for name, deck in decks(folder, case):
                    best = None
                    for _ in range(args.repeat):
                        r = run(os.path.abspath(exe), deck, os.path.join(folder, "out.h5"))
                        if r["status"] != "completed":
                            sys.exit(f"{exe} {case} {name}: status {r['status']}")
                        best = r if best is None or r["wall"] < best["wall"] else best
                    results[name] = best
                rows.append((case, exe, results))
    print("| case | executable | run | dofs | Newton it. | wall s | CPU s | peak MB | linear_solve s | "
          "elements s | contact s | projection + search |")
    print("|---|---|---|---|---|---|---|---|---|---|---|---|")
    for case, exe, results in rows:
        for name, r in results.items():
            c, t = r["counters"], r["timings"]
            search = t.get("projection", 0) + t.get("contact_search", 0)
            print(f"| {case} | {exe} | {name} | {c.get('dofs', '?')} | {c.get('total_newton_iterations', '?')} | "
                  f"{r['wall']:.2f} | {r['cpu']:.2f} | {r['rss_mb']:.0f} | {t.get('linear_solve', 0):.2f} | "
                  f"{t.get('elements', 0):.2f} | {t.get('contact', 0):.2f} | "
                  f"{search:.2f} s ({100 * search / t['total']:.1f} %) |")
    print()
    print("| case | executable | wall time ratio (target) | CPU time ratio | memory ratio (target) |")
    print("|---|---|---|---|---|")
    for case, exe, results in rows:
        w, wo = results["with contact"], results["without contact"]
        _, _, time_target, memory_target = CASES[case]
        tt = f" (<= {time_target:g})" if time_target else ""
        mt = f" (<= {memory_target:g})" if memory_target else ""
        print(f"| {case} | {exe} | {w['wall'] / wo['wall']:.2f}{tt} | {w['cpu'] / wo['cpu']:.2f} | "
              f"{w['rss_mb'] / wo['rss_mb']:.2f}{mt} |")


if __name__ == "__main__":
    main()
