"""Benchmark: machine dynamics' steady state. specs/four_bar.yaml on a motor curve with a
flywheel, simulated from rest to its steady state (the equation of motion, the integration,
the steady turn's analysis by every method); the issue's budget is 2 s of CPU. Then the same
at a mean speed (``mean_rpm``: the periodic state found directly by shooting), over one turn
and over a two-turn cycle (``cycle: 720``).

    OPENBLAS_NUM_THREADS=1 .venv/bin/python bench/bench_dynamics.py

Not a test: timings depend on the machine.
"""
from __future__ import annotations

import os

os.environ.setdefault("OPENBLAS_NUM_THREADS", "1")

import time  # noqa: E402
from pathlib import Path  # noqa: E402

from mechreport.dynamics import equation_of_motion, motion, simulate  # noqa: E402
from mechreport.model import build_mechanism  # noqa: E402
from mechreport.pipeline.analysis import analysis_of  # noqa: E402
from mechreport.pipeline.dynamics import run_dynamics  # noqa: E402
from mechreport.spec import parse_spec  # noqa: E402

ROOT = Path(__file__).resolve().parents[1]
DYNAMICS = """
dynamics:
  motor: {curve: [[0, 12], [250, 6], [320, 0]]}
  flywheel: 0.12
"""
MEAN_SPEED = """
dynamics:
  mean_rpm: 250
  flywheel: {inertia: 0.02, ratio: 2.5}
"""


def cpu(fn, repeat: int = 5) -> tuple[float, object]:
    best, out = float("inf"), None
    for _ in range(repeat):
        t = time.process_time()
        out = fn()
        best = min(best, time.process_time() - t)
    return best, out


def main() -> None:
    text = (ROOT / "specs" / "four_bar.yaml").read_text(encoding="utf-8")
    text = text.replace("mechreport: 1\n", "mechreport: 1.1\n") + DYNAMICS
    spec = parse_spec(text, "four_bar_motor_curve.yaml")
    mech = build_mechanism(spec)
    run_dynamics(mech, analysis_of)                      # warm: imports, caches
    t_eom, eom = cpu(lambda: equation_of_motion(mech))
    t_sim, sim = cpu(lambda: simulate(eom, spec.dynamics, spec.analysed_angles(), spec.file))
    t_all, dyn = cpu(lambda: run_dynamics(mech, analysis_of))
    print(f"steady after {sim.turns} turns ({sim.steady.t0 + sim.steady.period:.3g} s), "
          f"fluctuation {sim.steady.fluctuation:.4g}")
    print(f"equation of motion  {t_eom:6.3f} s CPU")
    print(f"simulation          {t_sim:6.3f} s CPU")
    print(f"steady state, all   {t_all:6.3f} s CPU (budget 2 s)")
    for cycle in (360, 720):
        mean = (ROOT / "specs" / "four_bar.yaml").read_text(encoding="utf-8").replace(
            "mechreport: 1\n", f"mechreport: 1.2\ncycle: {cycle}\n") + MEAN_SPEED
        # (the sweep stays one turn: the review's cycle quantities over two turns are h43a's)
        spec = parse_spec(mean, "four_bar_mean_rpm.yaml")
        mech = build_mechanism(spec)
        run_dynamics(mech, analysis_of)
        t_eom, eom = cpu(lambda: equation_of_motion(mech))
        t_sim, sim = cpu(lambda: motion(eom, spec.dynamics, spec.analysed_angles(), spec.file))
        t_all, dyn = cpu(lambda: run_dynamics(mech, analysis_of))
        print(f"mean_rpm, cycle {cycle}: fluctuation {sim.steady.fluctuation:.4g}, driving "
              f"torque {sim.drive_torque:.6g} N·m")
        print(f"equation of motion  {t_eom:6.3f} s CPU")
        print(f"periodic state      {t_sim:6.3f} s CPU")
        print(f"steady state, all   {t_all:6.3f} s CPU (budget 2 s)")

    for name in ("single_cylinder_engine", "inline_four_engine"):     # once they are merged
        path = ROOT / "specs" / f"{name}.yaml"
        if not path.exists():
            continue
        spec = parse_spec(path.read_text(encoding="utf-8")
                          + "\ndynamics:\n  mean_rpm: 3000\n  flywheel: 0.1\n", path.name)
        mech = build_mechanism(spec)
        run_dynamics(mech, analysis_of)
        t_all, dyn = cpu(lambda: run_dynamics(mech, analysis_of), repeat=3)
        print(f"{name} at mean_rpm 3000 over {spec.cycle:g}°: fluctuation "
              f"{dyn.values['dynamics.speed_fluctuation']:.4g}, all {t_all:6.3f} s CPU "
              "(budget 2 s)")


if __name__ == "__main__":
    main()
