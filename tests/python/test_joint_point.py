# SPDX-License-Identifier: MIT
"""The per-point joint behaviour (rockjoint.joint) works without the FE stack: in a process where
dolfinx, petsc4py, ufl and the FE extension cannot be imported, a Coulomb joint on a
Barton-Bandis law slips at the closed-form strength τ_y = c + σ_n tan φ, its normal stress is the
law's σ(Δ) = K_ni V_m Δ / (V_m - Δ), and its state carries the closed-form slip
(|j_s| - τ_y / k_s)."""
import os
import subprocess
import sys

SCRIPT = r'''
import importlib.abc, math, sys

class Blocked(importlib.abc.MetaPathFinder):
    """No FE stack: these imports fail as they would where DOLFINx is not installed."""
    def find_spec(self, name, path=None, target=None):
        if name.split(".")[0] in ("dolfinx", "petsc4py", "ufl", "basix") or name.endswith("_rockjoint_fem_coupling"):
            raise ImportError(f"{name} is blocked in this test")
        return None

sys.meta_path.insert(0, Blocked())
import rockjoint
from rockjoint.joint import JointBehaviour, ShearState, joint_response, make_strength

kni, vm, ks = 1e10, 1e-3, 4e9           # Barton-Bandis K_ni [Pa/m], V_m [m]; k_s [Pa/m]
phi, c = math.radians(30.0), 0.1e6      # Coulomb φ, c [Pa]
b = JointBehaviour(rockjoint.BartonBandis(kni, vm), shear_stiffness=ks,
                   strength=make_strength({"friction_angle": phi, "cohesion": c}))
closure, shear = 0.4e-3, 2e-3            # [m]: far past the elastic limit in shear
r = joint_response(b, [-closure, shear])
sigma_n = kni * vm * closure / (vm - closure)
tau_y = c + sigma_n * math.tan(phi)
assert abs(r["normal_stress"] - sigma_n) <= 1e-12 * sigma_n, (r["normal_stress"], sigma_n)
assert abs(r["traction"][1] - tau_y) <= 1e-9 * tau_y, (r["traction"][1], tau_y)
slip = shear - tau_y / ks
assert abs(r["state"].slip[0] - slip) <= 1e-12, (r["state"].slip[0], slip)
assert r["shear_state"] == ShearState.slip, r["shear_state"]
assert not any(m.split(".")[0] in ("dolfinx", "petsc4py", "ufl") for m in sys.modules)
print("ok")
'''


def test_joint_behaviour_needs_no_fe_stack(tmp_path):
    env = dict(os.environ, PYTHONPATH=os.pathsep.join(p for p in sys.path if p))
    r = subprocess.run([sys.executable, "-c", SCRIPT], capture_output=True, text=True, env=env,
                       cwd=tmp_path, timeout=120)
    assert r.returncode == 0 and r.stdout.strip() == "ok", r.stdout + r.stderr
