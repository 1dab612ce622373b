"""What every force method starts from: per-link inertia data, gravity, applied loads, and the
actions on any free body (a set of links), built once per analysis.

Conventions: a joint's reaction is the force (and, for T joints, the couple) that its first
link exerts on its second, global components: unknowns ``joint.J.fx``, ``joint.J.fy``,
``joint.J.moment``. On the first link it acts with sign -1 (textbook F21 = -F12). An R joint's
force acts at the pin; a T joint's at the slider's point, its couple about that point.
"""
from __future__ import annotations

from dataclasses import dataclass

import numpy as np

from ..kinematics import Kinematics
from ..model import Mechanism
from ..kinematics.frames import scaled
from ..spec import GROUND, Joint
from .equations import Action
from .loads import AppliedLoad, evaluate_loads

AXES = {"x": np.array([1.0, 0.0]), "y": np.array([0.0, 1.0])}
DRIVER_TORQUE = "driver.torque"   # an R driver's unknown; a T driver's is "driver.force"
_MISSING = object()               # ForceContext.once: no value yet (None is one)


def joint_point(kin: Kinematics, joint: Joint) -> np.ndarray:
    """Where a joint's reaction acts (n, 2) [m]: the pin, or the slider's point."""
    return kin.named_point(joint.point, _point_owner(joint)).r


def _point_owner(joint: Joint) -> str:
    """The link whose point a joint's reaction acts at."""
    return joint.links[1] if joint.type == "T" or joint.links[0] == GROUND else joint.links[0]


def _points_used(spec, loads) -> list[tuple[str, tuple]]:
    """(link, local point) of every point the force methods ask for: the centres of mass,
    where the joints' reactions act, where the loads act."""
    out = [(link.name, link.com) for link in spec.links]
    for j in spec.joints:
        owner = _point_owner(j)
        out.append((owner, spec.points_of(owner)[j.point]))
    out += [(ld.link, spec.points_of(ld.link)[ld.point]) for ld in loads if ld.force is not None]
    return out


def reaction_unknowns(joint: Joint) -> tuple[str, ...]:
    base = (f"joint.{joint.name}.fx", f"joint.{joint.name}.fy")
    return base + ((f"joint.{joint.name}.moment",) if joint.type == "T" else ())


@dataclass(frozen=True)
class LinkState:
    """Inertia data of a moving link over the sweep: centre of mass position ``r``, velocity
    ``v``, acceleration ``a`` (n, 2) [m, m/s, m/s^2]; ``omega``, ``alpha`` (n,); mass [kg],
    inertia about the centre of mass [kg m^2]."""

    name: str
    number: int
    mass: float
    inertia: float
    r: np.ndarray
    v: np.ndarray
    a: np.ndarray
    omega: np.ndarray
    alpha: np.ndarray


class ForceContext:
    """Inputs shared by all force methods for one solved kinematics."""

    def __init__(self, kin: Kinematics):
        self.kin = kin
        self.mech: Mechanism = kin.mechanism
        self.spec = self.mech.spec
        self.n = kin.n
        self.memo: dict = {}     # choices made once per analysis (the contour method's plan)
        self.plans = None        # a contour.ContourPlans shared by the specs of a batch
        self._joint_points: dict[str, np.ndarray] | None = None
        self.cache: dict = {}    # this context's own: actions per free body, coincidences
        self.gravity = np.asarray(self.spec.gravity, float)
        self.loads: list[AppliedLoad] = evaluate_loads(kin)
        kin.prepare_points(_points_used(self.spec, self.loads))
        self.links: dict[str, LinkState] = {}
        for link in self.spec.links:
            c = kin.com(link.name)
            k = link.number
            self.links[link.name] = LinkState(link.name, k, link.mass, link.inertia, c.r, c.v,
                                              c.a, kin.omega[:, k], kin.alpha[:, k])

    def num(self, link: str) -> int:
        return self.spec.number(link)

    @property
    def joint_points(self) -> dict[str, np.ndarray]:
        """Where each joint's reaction acts (n, 2): the pin, or the slider's point."""
        points = self._joint_points
        if points is None:   # (an attribute, not a cached_property: that would materialise
            # the instance's dict, and every read of the context's attributes would be slower)
            points = self._joint_points = {j.name: joint_point(self.kin, j)
                                           for j in self.spec.joints}
        return points

    def axis(self, name: str) -> np.ndarray:
        """The global unit vector ``x`` or ``y`` at every angle (n, 2), read-only."""
        return self.once(("axis", name), np.broadcast_to, AXES[name], (self.n, 2))

    def line_direction(self, joint: Joint) -> np.ndarray:
        """Unit direction (n, 2) of T joint ``joint``'s line in the global frame, read-only
        (every method and the slider's point ask for it)."""
        return self.once(("line", joint.name), self._line_direction, joint)

    def _line_direction(self, joint: Joint) -> np.ndarray:
        u = self.kin.frames.rotate(joint.guide, joint.line.direction)
        u.setflags(write=False)
        return u

    def point_of(self, name: str) -> np.ndarray:
        """Global position (n, 2) of a joint point or named point."""
        if name in self.joint_points:
            return self.joint_points[name]
        if name in self.spec.ground:     # one array per context (equations keyed by it)
            return self.once(("ground", name), np.broadcast_to,
                             np.asarray(self.spec.ground[name]), (self.n, 2))
        return self.kin.named_point(name).r

    def once(self, key: tuple, build, *args, keep=None):
        """``build(*args)``, computed once per context and ``key`` (actions are immutable).
        ``keep``: the objects whose ids are in ``key`` (arrays, actions), kept as long as the
        answer, so that those ids stay theirs. (The arguments, rather than a closure made
        at every call, hit or miss: hundreds of calls per analysis, most of them hits.)"""
        value = self.cache.get(key, _MISSING)
        if value is _MISSING:
            value = self.cache[key] = build(*args)
            if keep is not None:
                self.cache[("kept", key)] = keep
        return value

    def reaction(self, joint: Joint, on: str) -> list[Action]:
        """The joint's reaction as it acts on link ``on`` (one of its links)."""
        return list(self._reaction_once(joint, on))

    def _reaction_once(self, joint: Joint, on: str) -> tuple[Action, ...]:
        key = ("reaction", joint.name, on)
        acts = self.cache.get(key)      # (hits read directly: the hottest use of once)
        return acts if acts is not None else self.once(key, self._reaction, joint, on)

    def _reaction(self, joint: Joint, on: str) -> tuple[Action, ...]:
        a, b = joint.links
        sign = 1.0 if on == b else -1.0
        src, dst = (a, b) if on == b else (b, a)
        unknowns = reaction_unknowns(joint)
        acts = [Action(self.spec.symbol(src, dst), "force", "reaction", on, self.joint_points[joint.name], joint.point,
                       unknowns[:2], sign)]
        if joint.type == "T":
            acts.append(Action(self.spec.symbol(src, dst, "M"), "couple", "reaction", on,
                               unknowns=unknowns[2:], sign=sign))
        return tuple(acts) + self._friction(joint, on)

    def _friction(self, joint: Joint, on: str) -> tuple[Action, ...]:
        """The friction of ``joint`` on its link ``on`` (none without): an R joint's couple
        Mf, a T joint's force Ff along the line at the slider's point; the known values are
        the kinematics' (``Kinematics.friction``: on the second link, minus on the first).
        Part of the joint's actions, it stays in an equation written to eliminate the joint's
        reaction (a moment about its pin, a projection on its line)."""
        values = self.kin.friction
        if values is None or joint.name not in values:
            return ()
        a, b = joint.links
        src, dst = (a, b) if on == b else (b, a)
        m = (1.0 if on == b else -1.0) * values[joint.name]
        if joint.type == "R":
            return (Action(self.spec.symbol(src, dst, "Mf"), "couple", "friction", on,
                           value=m),)
        u = self.line_direction(joint)
        return (Action(self.spec.symbol(src, dst, "Ff"), "force", "friction", on,
                       self.joint_points[joint.name], joint.point, value=m[:, None] * u),)

    def gravity_action(self, link: str) -> Action:
        return self.once(("gravity", link), self._gravity_action, link)

    def _gravity_action(self, link: str) -> Action:
        s = self.links[link]
        weight = np.empty((self.n, 2))      # (np.broadcast_to costs more than the copy)
        weight[:] = scaled(s.mass, self.gravity)
        weight.setflags(write=False)
        return Action(f"G{s.number}", "force", "gravity", link, s.r, f"C{s.number}",
                      value=weight)

    def inertia_actions(self, link: str) -> list[Action]:
        """d'Alembert inertia force -m a_C at the centre of mass and couple -I alpha."""
        return list(self.once(("inertia", link), self._inertia_actions, link))

    def _inertia_actions(self, link: str) -> tuple[Action, ...]:
        s = self.links[link]
        return (Action(f"Fin{s.number}", "force", "inertia", link, s.r, f"C{s.number}",
                       value=-scaled(s.mass, s.a)),
                Action(f"Min{s.number}", "couple", "inertia", link, value=-s.inertia * s.alpha))

    def load_actions(self, link: str) -> list[Action]:
        return list(self.once(("loads", link), self._load_actions, link))

    def _load_actions(self, link: str) -> tuple[Action, ...]:
        acts = []
        for ld in self.loads:
            if ld.link != link:
                continue
            if ld.force is not None:
                at = self.kin.named_point(ld.point, link).r
                acts.append(Action(ld.symbol, "force", "load", link, at, ld.point,
                                   value=ld.force))
            else:
                acts.append(Action(ld.symbol, "couple", "load", link, value=ld.moment))
        return tuple(acts)

    @property
    def driver_unknown(self) -> str:
        """``driver.torque`` (R driver) or ``driver.force`` (T driver)."""
        return self.spec.driver.quantity

    def driver_actions(self, link: str) -> list[Action]:
        """The driver's effort as it acts on ``link``: a crank's motor torque M on the
        moving link; for an R driver between moving links, M on the second and -M on the
        first (the motor sits on the first); for a T driver, the push F along the line at the
        slider's point, +F on the second link and -F on the first."""
        return list(self.once(("driver", link), self._driver_actions, link))

    def _driver_actions(self, link: str) -> tuple[Action, ...]:
        d = self.spec.driver
        if link not in d.links:
            return ()
        unknown = (self.driver_unknown,)
        if d.crank:
            return (Action("M", "couple", "driver", link, unknowns=unknown),) \
                if link == d.link else ()
        sign = 1.0 if link == d.links[1] else -1.0
        if d.kind == "R":
            return (Action("M", "couple", "driver", link, unknowns=unknown, sign=sign),)
        joint = self.spec.joint(d.joint)
        u = self.line_direction(joint)
        return (Action("Fd", "force", "driver", link, self.joint_points[joint.name],
                       joint.point, unknowns=unknown, sign=sign, direction=u),)

    def actions_on(self, bodies, *, inertia: bool, exclude=()) -> list[Action]:
        """See :meth:`_actions_on`; built once per free body (methods share them)."""
        key = ("actions", tuple(bodies), inertia, tuple(exclude))
        acts = self.cache.get(key)
        if acts is None:
            acts = self.once(key, self._actions_on, bodies, inertia, exclude)
        return list(acts)

    def _actions_on(self, bodies, inertia: bool, exclude=()) -> tuple[Action, ...]:
        """Every external action on the free body made of ``bodies`` (moving links): reactions
        of joints that cross its boundary, gravity, loads, the driver torque, and (d'Alembert)
        the inertia forces and couples. Joints inside the body cancel and are left out (the
        driver too, when both its links are inside), and so are the joints named in
        ``exclude`` (those an equation is written to eliminate)."""
        body = set(bodies)
        acts: list[Action] = []
        for j in self.spec.joints:
            a, b = j.links
            if (a in body) != (b in body):
                on = a if a in body else b
                acts.extend(self._reaction_once(j, on) if j.name not in exclude else
                            self._friction(j, on))
        inner_driver = set(self.spec.driver.links) <= body   # its two sides cancel
        for link in bodies:
            acts.extend(self._link_actions(link, inertia, inner_driver))
        return tuple(acts)

    def _link_actions(self, link: str, inertia: bool, inner_driver: bool) -> tuple:
        """A link's own actions in a free body: inertia (d'Alembert), gravity, loads, and
        the driver's effort unless both its links are in the body."""
        key = ("own", link, inertia, inner_driver)
        own = self.cache.get(key)
        return own if own is not None else self.once(key, self._own_actions, link, inertia,
                                                     inner_driver)

    def _own_actions(self, link: str, inertia: bool, inner_driver: bool) -> tuple:
        acts = self.inertia_actions(link) if inertia else []
        acts.append(self.gravity_action(link))
        acts += self.load_actions(link)
        if not inner_driver:
            acts += self.driver_actions(link)
        return tuple(acts)
