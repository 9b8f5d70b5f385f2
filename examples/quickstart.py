#!/usr/bin/python3
"""Quick start: Hertz's cylinder on a rigid plane (scenes/hertz.json) from Python.

Run from anywhere:  /usr/bin/python3 examples/quickstart.py
(after the README's set-up, or with PYTHONPATH=build/python in a build tree).
"""
import os

import contactqp

scene = os.path.join(os.path.dirname(os.path.abspath(__file__)), "..", "scenes", "hertz.json")
r = contactqp.solve_scene(scene, backend=contactqp.Backend.ACTIVE_SET, tol=1e-8)

print(f"contactqp {contactqp.__version__}: {os.path.basename(scene)}, {r.dofs} DOFs, {r.constraints} contact candidates")
print(f"  {r.backend.label}: {r.status.label} after {r.iterations} iterations, "
      f"KKT residual {r.certificate.kkt_max:.1e}, relative duality gap {r.certificate.relative_gap:.1e}")
h = r.hertz
print(f"  force P = {r.contact.total_force:.6g} per unit length, {r.contact.contact_nodes} nodes in contact")
print(f"  half-width b  = {r.contact.half_width:.6g}  (Hertz {h.half_width:.6g}, error {100 * h.error_half_width:+.2f}%)")
print(f"  pressure p0   = {r.contact.max_pressure:.6g}  (Hertz {h.max_pressure:.6g}, error {100 * h.error_max_pressure:+.2f}%)")
print(f"  L2 error of the pressure profile against Hertz: {100 * h.error_l2:.2f}%")
print(f"  time: {r.timings['total']:.3f} s in all, {r.timings['solve']:.4f} s in the solver")
