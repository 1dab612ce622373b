"""The records of one analysis that results.csv and summary.json are written from, built
once (cached by :class:`~mechreport.pipeline.analysis.Analysis`): the results table (one row
per angle of the sweep) and the summary record (the effort, the reactions, the shaking, the
reference angles, the methods' agreement, the power balance, the left-out angles, the key
quantities, the design review and the friction). SI, the unit beside every value; the report
adds its title block and its words (:mod:`mechreport.report.records`)."""
from __future__ import annotations

import math

import numpy as np

from ..post.columns import sweep_rows
from ..post.friction import efficiency_undefined
from ..post.records import (friction_symbol, jnum, key_quantities, largest, peak_record,
                            reaction_symbols)
from ..post.sweep import PowerCheck
from ..quantities import joint_unit, unit_of
from ..units import RPM, deg, kind_of


def results_table(analysis) -> tuple[list[str], list[list[str]]]:
    """results.csv's header and rows: one row per angle of the sweep; left-out angles keep
    their row, with the reason in ``flag`` and empty cells; undefined values (NaN) are empty
    cells; round-off is 0."""
    columns = analysis.columns()
    names = [c.name for c in columns]
    data = np.column_stack([c.values for c in columns]) if columns else \
        np.zeros((analysis.kinematics.n, 0))
    rows = []
    for a, k, why in zip(*sweep_rows(analysis.angles, analysis.flags)):
        cells = ([""] * len(names) if k is None else
                 [f"{v:.10g}" if math.isfinite(v) else "" for v in data[k].tolist()])
        rows.append([deg(a), why, *cells])
    return [analysis.spec.axis_column, "flag", *names], rows


def power_record(pc: PowerCheck | None) -> dict | None:
    """The power balance's largest difference from the reference method (None unsolved)."""
    if pc is None:
        return None
    return {"max_abs_N_m": jnum(pc.max_abs), "relative": jnum(pc.relative),
            "angle_deg": pc.angle}


def summary_record(analysis) -> dict:
    """summary.json's results, from ``reference_method`` to ``strength`` (the report puts its
    title block and check line before them)."""
    spec = analysis.spec
    summary = analysis.sweep_summary()
    sc = analysis.scales()
    symbols = reaction_symbols(spec)
    st = summary.torque
    ref = summary.method
    F, M = sc["force"], sc["moment"]
    pushed = getattr(spec.driver, "kind", "R") == "T"      # a T driver pushes
    EU, ES = (unit_of("driver.force"), F) if pushed else (unit_of("driver.torque"), M)
    effort_key = "driver_force" if pushed else "driver_torque"
    big = summary.largest
    refs = {}
    for angle in spec.at:
        k = analysis.kinematics.index_of(angle)
        if k is None:
            continue
        refs[deg(angle)] = {
            effort_key: {m: jnum(r.driver_torque[k], ES) for m, r in analysis.forces.items()},
            "reactions": {j: {m: {"fx": jnum(r.reactions[j].fx[k], F),
                                  "fy": jnum(r.reactions[j].fy[k], F)}
                              for m, r in analysis.forces.items() if j in r.reactions}
                          for j in symbols},
            "units": {effort_key: EU, "reactions": "N"}}
    reported = analysis.forces[ref].reactions
    w = analysis.worst
    cycle = analysis.review.values if analysis.review is not None else {}
    if analysis.strength is not None:   # the members' quantities: key figures too (diff)
        cycle = {**cycle, **analysis.strength.values}
    return {
        "reference_method": ref, "n_angles": int(analysis.kinematics.n),
        "units": {"force": "N", "torque": "N·m", "moment": "N·m", "power": "W",
                  "length": "m", "angle": "deg", "note": "summary.json and results.csv are SI"},
        effort_key: None if st is None else {
            "unit": EU, "mean": jnum(st.mean, ES), "rms": jnum(st.rms, ES),
            "peak": peak_record(st.peak, EU, ES), "min": peak_record(st.low, EU, ES),
            "max": peak_record(st.high, EU, ES)},
        "driver_effort": "force" if EU == "N" else "torque",
        "mean_power": None if st is None else {"value": jnum(st.power), "unit": "W"},
        "reactions": {name: {"symbol": sym, "unit": "N",
                             "peak": peak_record(jl.peak, "N", F),
                             "peak_away_from_left_out": peak_record(jl.peak_far, "N", F),
                             "rms": None if jl.rms is None else jnum(jl.rms, F),
                             "fx_peak": peak_record(jl.fx_peak, "N", F),
                             "fy_peak": peak_record(jl.fy_peak, "N", F)}
                      for name, sym in symbols.items()
                      if name in reported and (jl := summary.joints[name])},
        "largest_bearing_load": None if big is None else {
            "joint": big[0], **peak_record(big[1], "N", F),
            "away_from_left_out": peak_record(summary.joints[big[0]].peak_far, "N", F)},
        "shaking": {"force_peak": peak_record(summary.shaking_force, "N", F),
                    "moment_peak": peak_record(summary.shaking_moment, "N·m", M)},
        "reference_angles": refs,
        "branches": [{"dyad": b.dyad, "type": b.kind, "rule": b.rule}
                     for b in analysis.kinematics.branches],
        "agreement": {
            "worst": None if w is None else {"quantity": w.quantity, "relative": w.relative,
                                             "absolute": w.absolute,
                                             "unit": spec.unit_of(w.quantity) or "N",
                                             "methods": list(w.methods), "angle_deg": w.angle},
            "quantities": [{"quantity": a.quantity, "relative": a.relative,
                            "absolute": a.absolute,
                            "unit": spec.unit_of(a.quantity) or "N",
                            "methods": list(a.methods),
                            "angle_deg": a.angle} for a in analysis.agreement]},
        "power_balance": power_record(summary.power_check),
        "residuals": [{"method": r.method, "force_N": r.force, "moment_N_m": r.moment}
                      for r in analysis.residuals],
        "flags": [{"angle_deg": f.angle, "kind": f.kind, "reason": f.reason}
                  for f in analysis.flags],
        "near_singular_deg": summary.near_deg,
        "notes": analysis.kinematics.notes(),
        "quantities": key_quantities(summary, cycle, sc, EU),
        "design": design_record(analysis, sc),
        "friction": friction_record(analysis, sc),
        "dynamics": dynamics_record(analysis),
        "strength": strength_record(analysis),
    }


def design_record(analysis, sc: dict) -> dict:
    """summary.json's ``design``: verdicts and cycle quantities, each value as in
    ``quantities`` (round-off of its kind made 0, :func:`~mechreport.post.records.jnum`)."""
    rev = analysis.review
    out: dict = {"verdicts": [{"item": v.item, "quantity": v.quantity, "value": jnum(v.value),
                               "limit": v.limit, "unit": v.unit, "lower_limit": v.at_least,
                               "margin": jnum(v.margin), "passed": v.passed,
                               "joint": v.where or None, "why": v.why or None}
                              for v in analysis.verdicts],
                 "cycle_undefined": analysis.review_problem or None}
    if rev is not None:
        out["cycle"] = {name: {"value": jnum(value, sc.get(kind_of(unit_of(name) or ""))),
                               "unit": unit_of(name)}
                        for name, value in rev.values.items()}
        out["method"] = rev.method
        out["interpolated_deg"] = [float(a) for a in rev.cycle.interpolated]
    return out


def friction_record(analysis, sc: dict) -> dict | None:
    """summary.json's ``friction`` (None without friction): per joint its data, its loss per
    cycle and largest value over the sweep; the energy lost per cycle and the efficiency
    (SI, with units; each value as in ``design.cycle``)."""
    spec, rev = analysis.spec, analysis.review
    if not spec.friction:
        return None
    losses = rev.friction if rev is not None else {}
    total = rev.values.get("cycle.friction.energy") if rev is not None else None
    joints = {}
    for fr in spec.friction:
        j = spec.joint(fr.joint)
        unit = joint_unit("friction", j.type)
        peak = largest((analysis.kinematics.friction or {}).get(fr.joint), analysis.angles)
        lost = losses.get(fr.joint)
        joints[fr.joint] = {
            "type": j.type, "symbol": friction_symbol(spec, j), "mu": fr.mu,
            "radius": None if fr.radius is None else {"value": fr.radius, "unit": "m"},
            "length": None if fr.length is None else {"value": fr.length, "unit": "m"},
            "energy_per_cycle": None if lost is None else {"value": jnum(lost), "unit": "J"},
            "share": jnum(lost / total) if lost is not None and total else None,
            "largest": None if peak is None else {
                "value": jnum(peak[0], sc.get("moment" if j.type == "R" else "force")),
                "unit": unit, "angle_deg": peak[1]}}
    eff = rev.values.get("cycle.efficiency") if rev is not None else None
    if rev is None:
        why = f"no cycle quantities: {analysis.review_problem}"
    else:
        why = None if eff is not None else efficiency_undefined(analysis.spec)
    return {"joints": joints,
            "energy_per_cycle": None if total is None else {"value": jnum(total), "unit": "J"},
            "efficiency": None if eff is None else {"value": jnum(eff), "unit": ""},
            "efficiency_undefined": why,
            "reversed_by_friction_deg": [float(a) for a in
                                         analysis.kinematics.reversed_by_friction],
            "left_out_deg": [f.angle for f in analysis.flags if f.by_friction]}


def dynamics_record(analysis) -> dict | None:
    """summary.json's ``dynamics`` (None without ``dynamics:``): the simulation's outcome,
    the ``dynamics.*`` quantities and the estimate (SI, with units)."""
    dyn = analysis.dynamics
    if dyn is None:
        return None
    sim, cycle = dyn.simulation, dyn.simulation.steady
    out = {"turns": sim.turns, "end_time": {"value": float(sim.time[-1]), "unit": "s"},
           "steady": cycle is not None, "histories": "dynamics.csv"}
    if cycle is not None:
        swing, inertia, estimate = dyn.estimate
        out.update({
            "quantities": {k: {"value": float(x), "unit": unit_of(k) or ""}
                           for k, x in dyn.values.items()},
            "period": {"value": cycle.period, "unit": "s"},
            "rpm_min": {"value": cycle.omega_min / RPM, "unit": "rpm"},
            "rpm_max": {"value": cycle.omega_max / RPM, "unit": "rpm"},
            "flywheel_estimate": {"speed_fluctuation": {"value": estimate, "unit": ""},
                                  "energy_fluctuation": {"value": swing, "unit": "J"},
                                  "inertia": {"value": inertia, "unit": "kg·m^2"}},
            "verdicts": [{"item": v.item, "passed": v.passed,
                          "value": None if v.value is None else float(v.value),
                          "limit": v.limit, "unit": v.unit}
                         for v in dyn.verdicts]})
    return out


def strength_record(analysis) -> dict | None:
    """summary.json's ``strength`` (None without a section): per member its quantities and
    where they occur, SI with units."""
    st = analysis.strength
    if st is None:
        return None
    out = {}
    for m in st.members.values():
        out[m.name] = {
            "link": m.link, "from": m.P, "to": m.Q, "length": {"value": m.length, "unit": "m"},
            "stress_max": {"value": m.stress_max, "unit": "Pa", "angle_deg": m.stress_angle,
                           "s_m": m.stress_s},
            "static_safety": m.static_safety,
            "fatigue_safety": m.fatigue_safety,
            "fatigue": {"s_m": m.fatigue_s, "sigma_a_Pa": m.sigma_a, "sigma_m_Pa": m.sigma_m},
            "buckling_safety": m.buckling_safety,
            "buckling": {"compression_N": m.compression,
                         "angle_deg": m.compression_angle,
                         "critical_load_N": m.critical_load, "slenderness": m.slenderness,
                         "rule": m.buckling_rule, "plane": m.buckling_plane},
            "note": m.note or None}
    return {"method": st.method, "members": out}
