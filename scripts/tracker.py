#!/usr/bin/env python3
"""An independent, exact front tracker for a layered elastic rod hitting a rigid wall.

Written from the paper ("Impact of composite soft-rigid elastic projectiles: A
numerical study": the d'Alembert solution, its Appendix B) and DESIGN.md, not
from the Rust engine, so that the two can check each other. Standard library
only.

The physics, in one place:

* A rod of elastic layers, stacked bottom (layer 0, at the wall) to top, each
  with length L, Young's modulus E and density rho; wave speed c = sqrt(E/rho),
  impedance Z = rho c, one-way transit time L/c. It moves down at v_b and
  touches a rigid wall at t = 0. The wall can push, never pull.
* Strain eps = du/dy and velocity v = du/dt. An up-going wave f(y - c t) has
  v = -c eps; a down-going wave g(y + c t) has v = +c eps. Starting from
  uniform fields, every field stays piecewise constant; a "front" is a jump d
  of strain carried up or down a layer, with the velocity jump -c d (up) or
  +c d (down). Front arrivals at the layer boundaries are the only events.
* At a boundary, the outgoing fronts follow from continuity of velocity and of
  stress E eps across it (derived in `interface_coefficients`). The free top
  end (stress zero) reflects d -> -d.
* The wall, in contact (bottom velocity held at 0): d -> +d, so the wall
  strain eps0 grows by 2d. If that would leave eps0 > 0 (tension), the rod
  separates instead: the reflected front makes eps0 = 0 and the bottom leaves
  at v0 = c0 (eps0 + 2d) > 0.
* The wall, separated (bottom free, stress zero): d -> -d and v0 += 2 c0 d;
  the bottom height z0 is piecewise linear. When it comes back to 0 with
  v0 < 0 the rod reconnects: an up-going front v0 / c0 is born at the wall
  and eps0 = v0 / c0.
* The wall pushes the rod with the force -E0 eps0 (unit cross-section), so the
  centre of mass velocity v_cm and displacement w_cm are known exactly
  (eps0 is piecewise constant). The restitution coefficient is e = v_cm / v_b
  at the end.
* The end. Once the rod is free with v_cm > 0, its bottom stays above
  w_cm(t) - D, where D = sqrt(int m(s)^2 / E(s) ds) sqrt(2 E_int) / M bounds
  how far the bottom can lag the centre of mass (Cauchy-Schwarz on
  w(0) - w_cm = -(1/M) int m(s) eps(s) ds, m(s) the mass above s, E_int the
  energy not in the centre-of-mass motion). So once w_cm >= D while free, the
  rod can never land again and the run stops. `--horizon F` stops at
  F max(transit times) instead, as the paper does with F = 20.

Fronts reaching the same boundary within a tiny time window (`--tie`, a
fraction of the total transit time) are combined before the boundary acts on
them: at the wall that matters, since the contact decision is not linear, and
commensurate transit times (t2 = n t1) make such ties common. Fronts whose
velocity jump c |d| is below `--drop` v_b are dropped and counted. There is
no other tolerance: the contact law is applied as stated (a wall strain that
would be tensile by any amount separates the rod).

Rounding. Near the paper's hard corner (alpha -> 0, x -> 1) the stiff bottom
layer chatters: it separates and lands again every few t1 with flights that
halve each time, until t_c. In double precision the flights soon fall under
the tie window and the chatter stops early; e moves by about 1e-12 (the
number of separations, not the paper's filtered bounce count N_b, depends on
the arithmetic). `--digits N` reruns everything in decimal arithmetic with N
significant digits to see this: e.g. --x 0.995 --alpha 0.005 separates 38
times in double precision, 99 times with 34 digits and 1396 times with 450.

Usage:
    python3 scripts/tracker.py --x 0.4 --alpha 0.05
    python3 scripts/tracker.py --x 0.995 --alpha 0.005 --json
    python3 scripts/tracker.py --scene data/scenes/three-layers.json
    python3 scripts/tracker.py --points points.txt     # lines "x alpha", JSON lines out
"""

from __future__ import annotations

import argparse
import heapq
import json
import math
import sys
import time
from dataclasses import dataclass
from decimal import Decimal, getcontext


def sqrt(value):
    """Square root of a float or a Decimal (see --digits)."""
    return value.sqrt() if isinstance(value, Decimal) else math.sqrt(value)


# Where a front arrives at a boundary from: the layer below it or above it.
FROM_BELOW = 0
FROM_ABOVE = 1


@dataclass(frozen=True)
class Layer:
    """One homogeneous elastic layer of unit cross-section."""

    length: float
    modulus: float
    density: float = 1.0

    @property
    def speed(self) -> float:
        return sqrt(self.modulus / self.density)

    @property
    def impedance(self) -> float:
        return self.density * self.speed

    @property
    def transit(self) -> float:
        return self.length / self.speed

    @property
    def mass(self) -> float:
        return self.density * self.length


def canonical_bilayer(x, alpha) -> list[Layer]:
    """The paper's bilayer: L = 1, rho = 1, E1 = 1 - alpha, E2 = alpha; layer 1 at the wall.
    x and alpha may be floats or Decimals; the layers are of the same type."""
    one = type(x)(1)
    return [Layer(one - x, one - alpha, one), Layer(x, alpha, one)]


def interface_coefficients(below: Layer, above: Layer) -> tuple[float, float, float, float]:
    """Strain reflection and transmission at an interface (the paper's R12, T12, R21, T21).

    An up-going front d from below gives r d (down, below) and t d (up, above):
    stress continuity  E_b (d + r d) = E_a t d,
    velocity continuity  c_b (r d - d) = -c_a t d   (v = -c eps up, +c eps down),
    so r = (Z_a - Z_b) / (Z_a + Z_b) and t = (E_b / E_a) 2 Z_a / (Z_a + Z_b).
    A down-going front from above is the mirror image.
    Returns (r_up, t_up, r_down, t_down).
    """
    zb, za = below.impedance, above.impedance
    r_up = (za - zb) / (za + zb)
    t_up = (below.modulus / above.modulus) * 2 * za / (za + zb)
    r_down = (zb - za) / (za + zb)
    t_down = (above.modulus / below.modulus) * 2 * zb / (za + zb)
    return r_up, t_up, r_down, t_down


def lag_bound_factor(layers: list[Layer]) -> float:
    """sqrt(int m(s)^2 / E(s) ds) / M: the bottom lags the centre of mass by at most
    this times sqrt(2 E_int). m(s) is the mass above height s, linear in each layer."""
    total_mass = sum(layer.mass for layer in layers)
    integral = 0
    mass_above = 0  # mass above the top of the current layer
    for layer in reversed(layers):
        rho = layer.density
        top, bottom = mass_above, mass_above + layer.mass
        # int over the layer of (mass_above + rho u)^2 / E du, u from 0 to length
        integral += (bottom**3 - top**3) / (3 * rho * layer.modulus)
        mass_above = bottom
    return sqrt(integral) / total_mass


@dataclass
class Result:
    restitution: float
    restitution_from_impulse: float
    contact_time: float
    separations: int
    bounces: int
    contacts: list[list[float]]
    transit_times: list[float]
    events: int
    dropped_fronts: int
    dropped_velocity: float
    end_time: float
    stop_reason: str
    elapsed_seconds: float = 0.0


def track(
    layers: list[Layer],
    impact_speed=None,
    drop: float = 1e-16,
    tie: float = 1e-12,
    horizon: float | None = None,
    max_events: int = 100_000_000,
) -> Result:
    """Trace every front from the first touch until the rod can never land again.

    drop: fronts whose velocity jump is below drop * impact_speed are dropped.
    tie: arrivals at one boundary closer than tie * (sum of transit times) are
         combined (treated as simultaneous).
    horizon: if given, stop at horizon * max(transit times) instead of the
         exact escape rule.
    """
    started = time.perf_counter()
    number = type(layers[0].modulus)  # float, or Decimal under --digits
    zero = number(0)
    impact_speed = number(1) if impact_speed is None else impact_speed
    n = len(layers)
    speeds = [layer.speed for layer in layers]
    transits = [layer.transit for layer in layers]
    interfaces = [None] + [interface_coefficients(layers[b - 1], layers[b]) for b in range(1, n)]
    total_mass = sum(layer.mass for layer in layers)
    wall_modulus, wall_speed = layers[0].modulus, speeds[0]
    tie_window = number(tie) * sum(transits)
    drop_velocity = number(drop) * impact_speed
    lag_factor = lag_bound_factor(layers)
    total_energy = total_mass * impact_speed**2 / 2
    stop_at = math.inf if horizon is None else number(horizon) * max(transits)

    # The fronts on their way: heap of (arrival time, boundary, FROM_BELOW or FROM_ABOVE, strain jump).
    # Boundary b sits at the top of layer b - 1 and the bottom of layer b; 0 is the wall, n the free top.
    fronts: list[tuple[float, int, int, float]] = []
    dropped = 0
    dropped_velocity = zero

    def launch(t: float, layer: int, upward: bool, jump: float) -> None:
        nonlocal dropped, dropped_velocity
        if abs(jump) * speeds[layer] < drop_velocity:
            dropped += 1
            dropped_velocity += abs(jump) * speeds[layer]
            return
        if upward:
            heapq.heappush(fronts, (t + transits[layer], layer + 1, FROM_BELOW, jump))
        else:
            heapq.heappush(fronts, (t + transits[layer], layer, FROM_ABOVE, jump))

    # The wall and the centre of mass.
    in_contact = True
    eps0 = -impact_speed / wall_speed  # strain at the wall: the first compression front
    v0 = zero  # bottom velocity (0 in contact)
    z0 = zero  # bottom height, valid at time t_bottom
    t_bottom = zero
    launch(zero, 0, True, eps0)

    v_cm, w_cm, t_cm = -impact_speed, zero, zero
    impulse_integral = zero  # int eps0 dt

    def advance_centre_of_mass(t: float) -> None:
        """Move v_cm and w_cm to time t under the constant wall strain eps0."""
        nonlocal v_cm, w_cm, t_cm, impulse_integral
        dt = t - t_cm
        acceleration = -wall_modulus * eps0 / total_mass
        w_cm += v_cm * dt + acceleration * dt * dt / 2
        v_cm += acceleration * dt
        impulse_integral += eps0 * dt
        t_cm = t

    contacts = [[zero, math.nan]]
    escape_time = math.inf  # once free with v_cm > 0: when w_cm reaches the lag bound
    events = 0
    stop_reason = "exhausted"
    t = zero

    while True:
        t = fronts[0][0] if fronts else math.inf

        if not in_contact:
            landing = t_bottom + z0 / -v0 if v0 < 0 else math.inf
            if landing <= t and landing < stop_at:
                # Reconnection: the wall stops the bottom and sends up a compression front.
                # (Before escape_time by construction: the lag bound forbids a later landing.)
                advance_centre_of_mass(landing)
                in_contact = True
                eps0 = v0 / wall_speed
                launch(landing, 0, True, eps0)
                v0, z0, t_bottom = zero, zero, landing
                escape_time = math.inf
                contacts.append([landing, math.nan])
                continue
            if t >= escape_time:
                t, stop_reason = escape_time, "escaped"
                break
        if t >= stop_at:
            t, stop_reason = stop_at, "horizon"
            break
        if not fronts:
            t, stop_reason = t_cm, "no fronts left"
            break
        if events >= max_events:
            stop_reason = "max_events"
            break

        # Every front arriving within the tie window, summed per boundary:
        # arriving[b] = [sum of jumps from below, sum of jumps from above].
        arriving: dict[int, list[float]] = {}
        while fronts and fronts[0][0] <= t + tie_window:
            _, boundary, side, jump = heapq.heappop(fronts)
            arriving.setdefault(boundary, [zero, zero])[side] += jump
            events += 1

        for boundary, (up, down) in arriving.items():
            if boundary == n:  # free top: reflect with the opposite sign
                launch(t, n - 1, False, -up)
            elif boundary > 0:  # interface between layers boundary - 1 and boundary
                r_up, t_up, r_down, t_down = interfaces[boundary]
                launch(t, boundary - 1, False, r_up * up + t_down * down)
                launch(t, boundary, True, t_up * up + r_down * down)
            elif in_contact:  # the wall pushes: rigid reflection, unless it would pull
                advance_centre_of_mass(t)
                if eps0 + 2 * down > 0:
                    # Separation: the reflected front leaves eps0 = 0, the bottom takes off.
                    reflected = -eps0 - down
                    v0 = wall_speed * (eps0 + 2 * down)
                    eps0 = zero
                    in_contact = False
                    z0, t_bottom = zero, t
                    contacts[-1][1] = t
                    if v_cm > 0 and horizon is None:
                        internal = max(total_energy - total_mass * v_cm**2 / 2, zero)
                        lag = lag_factor * sqrt(2 * internal)
                        escape_time = t + max(lag - w_cm, zero) / v_cm
                else:
                    reflected = down
                    eps0 += 2 * down
                launch(t, 0, True, reflected)
            else:  # free bottom: reflect with the opposite sign, the bottom speeds up
                z0 += v0 * (t - t_bottom)
                t_bottom = t
                v0 += 2 * wall_speed * down
                launch(t, 0, True, -down)

    advance_centre_of_mass(t)
    contact_time = contacts[-1][1] if not in_contact else math.nan
    shortest = min(transits)
    long_flights = sum(1 for a, b in zip(contacts, contacts[1:]) if b[0] - a[1] > shortest)
    return Result(
        restitution=v_cm / impact_speed,
        restitution_from_impulse=-1 - wall_modulus * impulse_integral / (total_mass * impact_speed),
        contact_time=contact_time,
        separations=len(contacts) - (1 if in_contact else 0),
        bounces=1 + long_flights,
        contacts=contacts,
        transit_times=transits,
        events=events,
        dropped_fronts=dropped,
        dropped_velocity=dropped_velocity,
        end_time=t,
        stop_reason=stop_reason,
        elapsed_seconds=time.perf_counter() - started,
    )


def load_scene(path: str, parse=float) -> tuple[list[Layer], float]:
    """A scene file with numeric layers, bottom first:
    {"impact_speed": v, "layers": [{"length": L, "modulus": E, "density": rho}, ...]}."""
    with open(path) as f:
        scene = json.load(f, parse_float=parse, parse_int=parse)
    layers = []
    for entry in scene["layers"]:
        if "modulus" not in entry or "density" not in entry:
            raise SystemExit(f"{path}: every layer needs a numeric modulus and density (materials are not looked up)")
        layers.append(Layer(entry["length"], entry["modulus"], entry["density"]))
    return layers, scene.get("impact_speed", parse(1))


def as_json(result: Result, **point) -> str:
    """One JSON object; Decimals (under --digits) are written as floats, e also as a string."""
    fields = dict(point)
    fields.update(
        restitution=result.restitution,
        restitution_from_impulse=result.restitution_from_impulse,
        contact_time=result.contact_time,
        separations=result.separations,
        bounces=result.bounces,
        events=result.events,
        dropped_fronts=result.dropped_fronts,
        dropped_velocity=result.dropped_velocity,
        end_time=result.end_time,
        stop_reason=result.stop_reason,
        transit_times=result.transit_times,
        contacts=result.contacts,
        elapsed_seconds=result.elapsed_seconds,
    )
    if isinstance(result.restitution, Decimal):
        fields["restitution_digits"] = str(result.restitution)

    def plain(value):
        if isinstance(value, list):
            return [plain(v) for v in value]
        return float(value) if isinstance(value, Decimal) else value

    return json.dumps({key: plain(value) for key, value in fields.items()})


def summary(result: Result, title: str) -> str:
    lines = [
        title,
        f"  restitution e        {result.restitution:.12f}  (from the wall impulse: {result.restitution_from_impulse:.12f})",
        f"  contact time t_c     {result.contact_time:.10g}",
        f"  separations          {result.separations}  (bounces N_b {result.bounces})",
        f"  transit times        {', '.join(f'{t:.6g}' for t in result.transit_times)}",
        f"  stopped at t = {result.end_time:.6g}  ({result.stop_reason})",
        f"  events               {result.events} in {result.elapsed_seconds * 1e3:.2f} ms;"
        f" dropped {result.dropped_fronts} fronts (sum of velocity jumps {float(result.dropped_velocity):.1e} v_b)",
    ]
    return "\n".join(lines)


def read_points(path: str, parse=float) -> list[tuple]:
    """Lines of "x alpha" (spaces or a comma between); blank lines and # comments skipped."""
    text = sys.stdin.read() if path == "-" else open(path).read()
    points = []
    for line in text.splitlines():
        words = line.split("#", 1)[0].replace(",", " ").split()
        if words:
            points.append((parse(words[0]), parse(words[1])))
    return points


def main() -> None:
    parser = argparse.ArgumentParser(
        description=__doc__.split("\n\n")[0], epilog="Canonical bilayer: L = 1, rho = 1, E1 = 1 - alpha, E2 = alpha, v_b = 1."
    )
    parser.add_argument("--x", help="composition x = L2 / L of the canonical bilayer, in (0, 1)")
    parser.add_argument("--alpha", help="stiffness ratio alpha = E2 / (E1 + E2), in (0, 1)")
    parser.add_argument("--scene", help="scene JSON with numeric layers (bottom first)")
    parser.add_argument("--points", help='file of "x alpha" lines (- for stdin): one JSON line per point')
    parser.add_argument("--json", action="store_true", help="print one JSON object")
    parser.add_argument("--drop", type=float, default=1e-16, help="drop fronts whose velocity jump is below DROP v_b")
    parser.add_argument(
        "--tie", type=float, help="combine arrivals closer than TIE sum(t_i) (default 1e-12; 10^(4 - DIGITS) with --digits)"
    )
    parser.add_argument("--horizon", type=float, help="stop at HORIZON max(t_i) instead of the exact escape rule")
    parser.add_argument("--digits", type=int, help="compute in decimal arithmetic with DIGITS significant digits")
    args = parser.parse_args()

    parse = float
    tie = 1e-12 if args.tie is None else args.tie
    if args.digits:
        getcontext().prec = args.digits
        parse = Decimal
        tie = 10.0 ** (4 - args.digits) if args.tie is None else args.tie
    options = dict(drop=args.drop, tie=tie, horizon=args.horizon)

    if args.points:
        for x, alpha in read_points(args.points, parse):
            print(as_json(track(canonical_bilayer(x, alpha), **options), x=x, alpha=alpha), flush=True)
        return
    if args.scene:
        layers, speed = load_scene(args.scene, parse)
        result = track(layers, speed, **options)
        print(as_json(result, scene=args.scene) if args.json else summary(result, f"Scene {args.scene}"))
        return
    if args.x is None or args.alpha is None:
        parser.error("give --x and --alpha, --scene or --points")
    x, alpha = parse(args.x), parse(args.alpha)
    for name, value in (("--x", x), ("--alpha", alpha)):
        if not 0 < value < 1:
            parser.error(f"{name} must be in (0, 1), got {args.x if name == '--x' else args.alpha}")
    result = track(canonical_bilayer(x, alpha), **options)
    title = f"Canonical bilayer x = {args.x}, alpha = {args.alpha}"
    print(as_json(result, x=x, alpha=alpha) if args.json else summary(result, title))


if __name__ == "__main__":
    main()
