#!/usr/bin/python3
"""Runs getfem_hertz.py over the meshes (or the formulation parameters) of the README table and
writes one CSV row per run plus a Markdown table on stdout.

    /usr/bin/python3 benchmarks/peers/getfem_table.py --study meshes --out-dir OUT [--order 2]
    /usr/bin/python3 benchmarks/peers/getfem_table.py --study parameters --out-dir OUT
    /usr/bin/python3 benchmarks/peers/getfem_table.py --study meshes --out-dir OUT \
        --contact-sizes 0.016,0.008 --formulations integral,nodal --csv getfem.csv

meshes: the Hertz scene (R = 1, E = 1, nu = 0.3, delta = 0.016, symmetry) with contact_size
0.004, 0.002, 0.001, 0.0005 and size = 50 contact_size (scenes/hertz.json is the 0.002 row),
GetFEM's default formulation, order 1 (or --order 2); each mesh is kept in OUT as
mesh_o<order>_cs<contact_size>.msh with its .geo.
--contact-sizes and --formulations choose other meshes and formulations (benchmarks/tradeoff runs
both multiplier formulations on its meshes); --csv writes the CSV elsewhere.
parameters: the 0.002 mesh with each formulation and a range of its parameter.
"""

import argparse
import csv
import json
import os
import subprocess
import sys

HERE = os.path.dirname(os.path.abspath(__file__))
SCENE = ["--radius", "1", "--E", "1", "--nu", "0.3", "--delta", "0.016", "--symmetry"]
MESHES = [0.004, 0.002, 0.001, 0.0005]
PARAMETERS = ([("integral", r, 0.0) for r in (0.1, 1.0, 10.0, 100.0)] +
              [("nodal", r, 0.0) for r in (0.1, 1.0, 10.0, 100.0)] +
              [("nitsche", g, theta) for theta in (0.0, -1.0, 1.0) for g in (0.01, 0.1, 1.0, 10.0)])
COLUMNS = ["formulation", "param", "theta", "order", "contact_size", "size", "dofs", "unknowns", "nodes",
           "elements", "converged", "newton_iterations", "seconds", "seconds_newton", "seconds_mesh",
           "total_force", "half_width", "max_pressure", "error_half_width", "error_max_pressure", "error_l2"]


def run(out_dir, contact_size, formulation="integral", param=1.0, theta=0.0, order=1, repeat=3, keep_mesh=True):
    tag = f"{formulation}_p{param:g}_t{theta:g}_o{order}_cs{contact_size:g}"
    out = os.path.join(out_dir, tag + ".json")
    command = [sys.executable, os.path.join(HERE, "getfem_hertz.py"), *SCENE,
               "--size", f"{50 * contact_size:g}", "--contact-size", f"{contact_size:g}",
               "--formulation", formulation, "--param", f"{param:g}", "--theta", f"{theta:g}",
               "--order", str(order), "--repeat", str(repeat), "--out", out]
    if keep_mesh:
        command += ["--msh", os.path.join(out_dir, f"mesh_o{order}_cs{contact_size:g}.msh")]
    print("  " + " ".join(command[1:]), file=sys.stderr, flush=True)
    finished = subprocess.run(command, capture_output=True, text=True)
    print("    " + (finished.stdout.strip() or finished.stderr.strip()), file=sys.stderr, flush=True)
    if not os.path.exists(out) or finished.returncode == 2:
        return None
    result = json.load(open(out))
    hertz = result.get("hertz") or {}
    row = {"formulation": formulation, "param": param, "theta": theta, "order": order,
           "contact_size": contact_size, "size": 50 * contact_size}
    row.update({key: result[key] for key in COLUMNS if key in result})
    row.update({key: hertz.get(key, "") for key in ("error_half_width", "error_max_pressure", "error_l2")})
    return row


def percent(value):
    return f"{100 * value:+.2f}%" if isinstance(value, float) else "–"


def markdown(rows, study):
    if study == "meshes":
        several = len({r["formulation"] for r in rows}) > 1
        lines = ["| " + ("formulation | " if several else "") +
                 "contact_size | size | DOFs | Newton it. | time [s] (Newton) | mesh [s] | P | b error | p0 error | L2 error |",
                 "|" + ("---|" if several else "") + "---:|---:|---:|---:|---:|---:|---:|---:|---:|---:|"]
        for r in rows:
            lines.append("| " + (f"{r['formulation']} | " if several else "") + f"{r['contact_size']:g} | {r['size']:g} | {r['dofs']} | {r['newton_iterations']} | "
                         f"{r['seconds']:.3f} ({r['seconds_newton']:.3f}) | {r['seconds_mesh']:.3f} | "
                         f"{r['total_force']:.7f} | {percent(r['error_half_width'])} | "
                         f"{percent(r['error_max_pressure'])} | {percent(r['error_l2']).lstrip('+')} |")
    else:
        lines = ["| formulation | parameter | θ | converged | Newton it. | time [s] | P | b error | p0 error | L2 error |",
                 "|---|---:|---:|---|---:|---:|---:|---:|---:|---:|"]
        for r in rows:
            name = "r/E" if r["formulation"] != "nitsche" else "γ0·E"
            theta = f"{r['theta']:g}" if r["formulation"] == "nitsche" else ""
            lines.append(f"| {r['formulation']} | {name} = {r['param']:g} | {theta} | {'yes' if r['converged'] else 'no'} | "
                         f"{r['newton_iterations']} | {r['seconds']:.3f} | {r['total_force']:.7f} | "
                         f"{percent(r['error_half_width'])} | {percent(r['error_max_pressure'])} | "
                         f"{percent(r['error_l2']).lstrip('+')} |")
    return "\n".join(lines)


def sizes(text):
    values = [float(v) for v in text.split(",")]
    if not values or not all(v > 0 for v in values):
        raise argparse.ArgumentTypeError(f"{text!r}: positive numbers separated by commas")
    return values


def formulations(text):
    names = text.split(",")
    if not names or not all(n in ("integral", "nodal", "nitsche") for n in names):
        raise argparse.ArgumentTypeError(f"{text!r}: integral, nodal or nitsche, separated by commas")
    return names


def main():
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--study", choices=("meshes", "parameters"), default="meshes")
    parser.add_argument("--out-dir", required=True)
    parser.add_argument("--repeat", type=int, default=3)
    parser.add_argument("--order", type=int, choices=(1, 2), default=1, help="element order of the meshes study")
    parser.add_argument("--contact-sizes", type=sizes, default=MESHES,
                        help="meshes study: comma-separated contact sizes (size = 50 x each)")
    parser.add_argument("--formulations", type=formulations, default=["integral"],
                        help="meshes study: comma-separated formulations (integral, nodal, nitsche)")
    parser.add_argument("--csv", help="the CSV (default: OUT/getfem_<study>[_order<k>].csv)")
    args = parser.parse_args()
    os.makedirs(args.out_dir, exist_ok=True)
    if args.study == "meshes":
        jobs = [dict(contact_size=cs, order=args.order, formulation=f) for f in args.formulations
                for cs in args.contact_sizes]
    else:
        jobs = [dict(contact_size=0.002, formulation=f, param=p, theta=t, keep_mesh=False) for f, p, t in PARAMETERS]
    rows = [row for row in (run(args.out_dir, repeat=args.repeat, **job) for job in jobs) if row]
    name = f"getfem_{args.study}" + (f"_order{args.order}" if args.study == "meshes" else "")
    with open(args.csv or os.path.join(args.out_dir, name + ".csv"), "w", newline="") as stream:
        writer = csv.DictWriter(stream, fieldnames=COLUMNS, extrasaction="ignore")
        writer.writeheader()
        writer.writerows(rows)
    print(markdown(rows, args.study))
    return 0 if len(rows) == len(jobs) else 1


if __name__ == "__main__":
    sys.exit(main())
