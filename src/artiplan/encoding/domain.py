"""PDDL+ domains for the three gravity models (NG, UCM, UACM), generated from options.

The constructs and their names are the paper's (start-/stop-increase, move-, propagate-,
back-to-zero/back-to-360, gravity-increase/-decrease, ...). Where the generated text departs
from the published models it is for correctness under VAL's semantics (shared/docs/stack.md);
each departure is marked ``DEPARTURE`` below and explained in docs/encodings.md:

1. Wrap-around: ``back-to-zero`` fires at ``>= 360`` and assigns 0; ``back-to-360`` fires at
   ``<= -m`` and assigns 360 - m (``m`` = ``EncodingOptions.margin``, 0.2 deg at 10 deg/s). No
   event lands within VAL's comparison slack (1e-4) of another event's boundary, so wraps
   never bounce, and no two events of one motion fall within VAL's 0.01 s event window;
   angles live in [-m, 360). (Adding or subtracting 360 instead would keep a fixed-step
   planner's overshoot, but it made ENHSP's heuristic solve 5 instead of 9 of 10 small NG
   problems: benchmarks/results/encoding.md.) Each wrap sets a flag its own precondition
   excludes (``wrapped-to-zero``/``wrapped-to-360``), cleared by the other wrap or a quarter
   turn later, so that VAL sees every wrap falsify its precondition even when it fires the
   wrap a rounding error early.
2. Processes have only continuous effects (VAL rejects Booleans in processes): "gravity acts on
   l" is derived from the state. ``(link-index ?l)`` is static; ``(held-index)`` is the index of
   the link being rotated (1 when the hands are free: L1 is always clamped). A link feels
   gravity when its index exceeds ``held-index`` (it is not held and no held link is tip-ward of
   it). The comparison is against ``held-index + 0.5`` so that VAL's slack on strict
   comparisons can never make equal integers compare greater.
3. UCM and UACM: gravity is switched by events with Boolean flags
   (``decreasing-angle-gravity``/``increasing-angle-gravity``) that read only the angle, and
   the processes read the flags and "feels gravity" (changed only by actions): every process
   starts and stops at a happening, and no action triggers an event (what VAL needs, see
   docs/encodings.md "Gravity"). Start and stop thresholds are ``m`` apart (hysteresis) so a
   stop event never re-enables its start event; the problem starts with the flags its angles
   imply. UACM's speeds are reset to 0 by the events and, for the links a grasp stops, by the
   grasp itself.
4. ``observe``: a no-effect action, so a plan can end when a process completes the goal.
"""

from __future__ import annotations

from artiplan.encoding.goals import fmt_number
from artiplan.encoding.options import EncodingOptions
from artiplan.model import ArticulatedObject

#: Smallest margin [deg] of the wrap-around below 0 and of the gravity flags' hysteresis (the
#: margin used is ``EncodingOptions.margin``, which also scales with the robot's speed).
WRAP_MARGIN = 0.01

#: Angles [deg] at which a wrap's flag is cleared again (``rearm-back-to-zero`` at or above
#: 90, ``rearm-back-to-360`` at or below 270): a link can reach the same wrap again only by
#: passing one of them or by the other wrap, which clears the flag too; both lie a quarter
#: turn from every gravity threshold (0 and 180).
REARM_ZERO = 90.0
REARM_360 = 270.0

#: With ``EncodingOptions.refusals``: a turn unlocks what the robot refused (a pair's start, a
#: link it could not grasp) only once it has gone this far [deg]. Measured: with any turn
#: counting, plans unlocked refusals with 1 ms turns (up to 47 in one 6-link run) that moved
#: nothing, and the robot refused the same grasps again.
CLEAR_DEG = 10.0
#: The same for a link no hand could grasp (``blocked-hold``/``blocked-turn``, cleared by
#: ``turned-far``) [deg]. Such a link's grasps met a neighbour folded against it; measured on
#: 4-link pushed tasks (sessions 23-24): folds of 123-175 deg, where a turn of 10 deg freed
#: none of the grasps and the plans spent up to 39 refusals on them. A turn of 25 deg for every
#: refusal opened one such fold (task 13) but cost a task whose refusals were arm motions not
#: found (42 refusals): so only the grasps wait for the larger turn.
CLEAR_FAR_DEG = 25.0


def domain_name(options: EncodingOptions) -> str:
    """The domain's name: ``artiplan-ng``, ``artiplan-ucm`` or ``artiplan-uacm``."""
    return f"artiplan-{options.model}"


def _header(options: EncodingOptions) -> str:
    planes = " ".join(options.planes)
    functions = ["(angle ?l - link ?p - plane)", "(speed-i)", "(speed-d)"]
    predicates = [
        "(in-use)",
        "(free-to-move ?l - link)",
        "(connected ?l1 - link ?l2 - link)",
        "(affects ?l1 - link ?l2 - link)",
        "(increasing-angle-robot ?l - link ?p - plane)",
        "(decreasing-angle-robot ?l - link ?p - plane)",
        "(wrapped-to-zero ?l - link ?p - plane)",
        "(wrapped-to-360 ?l - link ?p - plane)",
    ]
    if options.has_gravity:
        functions += ["(link-index ?l - link)", "(held-index)"]
    if options.model == "ucm":
        functions.append("(speed-g)")
    if options.torque_fall:
        functions.append("(fall ?l - link)")
        predicates.append("(tilts ?p - plane)")
    if options.model == "uacm":
        functions += ["(acceleration)", "(gravity-speed ?l - link)"]
    if options.has_gravity:
        predicates += [
            "(increasing-angle-gravity ?l - link)",
            "(decreasing-angle-gravity ?l - link)",
        ]
    if options.has_reach:
        functions += ["(reach-time)", "(reach-clock)"]
        predicates.append("(reaching)")
    if options.refusals:
        predicates += ["(refused-increase ?l1 - link ?l2 - link ?p - plane)",
                       "(refused-decrease ?l1 - link ?l2 - link ?p - plane)",
                       "(unlocked ?l - link)",
                       "(blocked-hold ?l - link)", "(blocked-turn ?l - link)",
                       "(clears ?l1 - link ?l2 - link)", "(cleared ?l - link)",
                       "(turned-enough)", "(turned-far)"]
    if options.counts_turn:
        functions.append("(turned)")
    if options.carry == "projected":
        functions.append("(carry ?l1 - link ?l2 - link ?p - plane)")
        if options.azimuth_plane:
            functions.append("(carry-theta ?l1 - link ?l2 - link)")
    pred_text = "\n    ".join(predicates)
    func_text = "\n    ".join(functions)
    return f"""(define (domain {domain_name(options)})
  (:requirements :strips :typing :negative-preconditions :disjunctive-preconditions
    :fluents :time{" :conditional-effects" if options.model == "uacm" or options.refusals
                   else ""})
  (:types link plane)
  (:constants {planes} - plane)
  (:predicates
    {pred_text})
  (:functions
    {func_text})
"""


def _robot(options: EncodingOptions, sign: str) -> str:
    """start-/stop-, move- and propagate- for one direction (``increase`` or ``decrease``)."""
    flag = f"{sign}ing-angle-robot".replace("eing", "ing")
    speed = "(speed-i)" if sign == "increase" else "(speed-d)"
    held_start = "\n      (assign (held-index) (link-index ?l2))" if options.has_gravity else ""
    if options.model == "uacm":
        # A grasp stops the falls of ?l2 and every link base-ward of it (those ?l2 does not
        # carry): their speeds restart from 0. An action effect, not an event (see the gravity
        # flags); a fact condition, because ENHSP fails on numeric conditions in `when`.
        held_start += """
      (forall (?l - link)
        (when (not (affects ?l2 ?l))
          (assign (gravity-speed ?l) 0)))"""
    held_stop = "\n      (assign (held-index) 1)" if options.has_gravity else ""
    timed = options.has_reach
    ready = "\n      (not (reaching))" if timed else ""
    reach = "\n      (reaching)\n      (assign (reach-clock) 0)" if timed else ""
    moved, within = "", ""
    if options.counts_turn:
        held_start += "\n      (assign (turned) 0)"
        moved = f"\n      (increase (turned) (* #t {speed}))"
    if options.max_turn_deg is not None:
        within = f"\n      (<= (turned) {fmt_number(options.max_turn_deg)})"
    if options.refusals:
        # A refused start waits until its rotated link (and so the pair) has moved: a turn
        # of that link or of one base-ward of it has stopped (a turn further out does not
        # move the pair). A link no hand could grasp (in a role) waits until it has moved
        # relative to what its grasps met: a turn of a link between them ((clears ?l2 ?l),
        # from the problem). The first after a turn of CLEAR_DEG or more, the second after
        # one of CLEAR_FAR_DEG.
        ready += (f"\n      (or (unlocked ?l2) (not (refused-{sign} ?l1 ?l2 ?p)))"
                  "\n      (or (cleared ?l1) (not (blocked-hold ?l1)))"
                  "\n      (or (cleared ?l2) (not (blocked-turn ?l2)))")
        held_start += "\n      (not (turned-enough))\n      (not (turned-far))"
        reach += ("\n      (when (turned-enough) (unlocked ?l2))\n      (forall (?l - link)"
                  "\n        (when (and (turned-enough) (affects ?l2 ?l)) (unlocked ?l)))"
                  "\n      (forall (?l - link)"
                  "\n        (when (and (turned-far) (clears ?l2 ?l)) (cleared ?l)))")
    if options.torque_fall:
        # The factors are the percept's geometry: links the robot tilts (a turn on the gravity
        # plane) fall at the paper's uniform speed from then on (their new torques are not
        # modelled); a turn about the vertical leaves every gravity torque as it was.
        held_start += ("\n      (when (tilts ?p) (assign (fall ?l2) 1))\n      (forall (?l - link)"
                       "\n        (when (and (tilts ?p) (affects ?l2 ?l)) (assign (fall ?l) 1)))")
    carried = _carried(options, speed, "?p")
    turning = f"({flag} ?l1 {options.gravity_plane})\n      (affects ?l1 ?l2)"
    azimuth = _azimuth(options, f"propagate-{sign}-azimuth", turning, sign, speed)
    return f"""
  ;; The robot holds ?l1 with one hand and rotates its tip-ward neighbour ?l2 on ?p.
  (:action start-{sign}
    :parameters (?l1 - link ?l2 - link ?p - plane)
    :precondition (and
      (connected ?l1 ?l2)
      (not (in-use)){ready})
    :effect (and
      (in-use)
      (not (free-to-move ?l1))
      (not (free-to-move ?l2))
      ({flag} ?l2 ?p){held_start}))

  (:action stop-{sign}
    :parameters (?l1 - link ?l2 - link ?p - plane)
    :precondition (and
      (connected ?l1 ?l2)
      ({flag} ?l2 ?p){within})
    :effect (and
      (not (in-use))
      (free-to-move ?l1)
      (free-to-move ?l2)
      (not ({flag} ?l2 ?p)){held_stop}{reach}))

  (:process move-{sign}
    :parameters (?l - link ?p - plane)
    :precondition ({flag} ?l ?p)
    :effect (and ({sign} (angle ?l ?p) (* #t {speed})){moved}))

  ;; The rotation carries every link tip-ward of ?l1 (absolute angles move together).
  (:process propagate-{sign}
    :parameters (?l1 - link ?l2 - link ?p - plane)
    :precondition (and
      ({flag} ?l1 ?p)
      (affects ?l1 ?l2))
    :effect (and ({sign} (angle ?l2 ?p) (* #t {carried}))))
{azimuth}"""


def _azimuth(options: EncodingOptions, name: str, when: str, sign: str, rate: str) -> str:
    """``projected`` carry: process ``name`` in which a vertical turn of ?l1 (going on while
    ``when`` holds, at ``rate``) also moves the azimuth of the carried ?l2, at ``rate`` times
    the problem constant ``(carry-theta ?l1 ?l2)``. Empty for the rigid carry."""
    h = options.azimuth_plane
    if h is None:
        return ""
    return f"""
  ;; A vertical turn of ?l1 also turns a carried ?l2 about the vertical unless ?l2 lies in
  ;; ?l1's plane (projected carry; the factor is fixed at the problem's start).
  (:process {name}
    :parameters (?l1 - link ?l2 - link)
    :precondition (and
      {when})
    :effect (and ({sign} (angle ?l2 {h}) (* #t (* {rate} (carry-theta ?l1 ?l2))))))
"""

def _carried(options: EncodingOptions, rate: str, plane: str) -> str:
    """The rate at which a carried link ?l2 follows ?l1's ``rate`` on ``plane``."""
    if options.carry == "projected":
        return f"(* {rate} (carry ?l1 ?l2 {plane}))"
    return rate


def _wrap_events(options: EncodingOptions) -> str:
    m = fmt_number(options.margin)
    return f"""
  ;; DEPARTURE (VAL): wrap below 0 only at -{m} and land on 360 - {m}, so that no wrap lands
  ;; within VAL's comparison slack of the other's boundary (no bouncing), and no two events of
  ;; a motion fall within VAL's event window of each other. Angles: [-{m}, 360).
  ;; A wrap sets a flag that its precondition excludes, and crossing 90 (270) re-arms it: VAL
  ;; fires a wrap due a rounding error after another object's event in a second round and
  ;; then finds its numeric precondition still true; a flag is falsified whatever the arithmetic.
  (:event back-to-zero
    :parameters (?l - link ?p - plane)
    :precondition (and
      (>= (angle ?l ?p) 360)
      (not (wrapped-to-zero ?l ?p)))
    :effect (and
      (assign (angle ?l ?p) 0)
      (wrapped-to-zero ?l ?p)
      (not (wrapped-to-360 ?l ?p))))

  (:event back-to-360
    :parameters (?l - link ?p - plane)
    :precondition (and
      (<= (angle ?l ?p) -{m})
      (not (wrapped-to-360 ?l ?p)))
    :effect (and
      (assign (angle ?l ?p) {fmt_number(360 - options.margin)})
      (wrapped-to-360 ?l ?p)
      (not (wrapped-to-zero ?l ?p))))

  (:event rearm-back-to-zero
    :parameters (?l - link ?p - plane)
    :precondition (and
      (wrapped-to-zero ?l ?p)
      (>= (angle ?l ?p) {fmt_number(REARM_ZERO)}))
    :effect (and (not (wrapped-to-zero ?l ?p))))

  (:event rearm-back-to-360
    :parameters (?l - link ?p - plane)
    :precondition (and
      (wrapped-to-360 ?l ?p)
      (<= (angle ?l ?p) {fmt_number(REARM_360)}))
    :effect (and (not (wrapped-to-360 ?l ?p))))
"""


def _feels(var: str) -> str:
    """Condition: gravity can act on link ``var`` (not held, no held link tip-ward of it)."""
    return f"(> (link-index {var}) (+ (held-index) 0.5))"


def _gravity(options: EncodingOptions, sign: str) -> str:
    """Gravity on one side of the vertical (``decrease``: (0, 180), ``increase``: (180, 360)),
    switched by flag events; UCM moves at ``(speed-g)``, UACM at ``(gravity-speed ?l)``."""
    g = options.gravity_plane
    flag = f"{sign}ing-angle-gravity".replace("eing", "ing")
    other = "increasing-angle-gravity" if sign == "decrease" else "decreasing-angle-gravity"
    m = fmt_number(options.hysteresis)
    uacm = options.model == "uacm"
    rate = "(gravity-speed ?l)" if uacm else "(speed-g)"
    if options.torque_fall:
        rate = "(* (speed-g) (fall ?l))"
    rate1 = rate.replace("?l)", "?l1)")
    reset = "\n      (assign (gravity-speed ?l) 0)" if uacm else ""
    azimuth = _azimuth(options, f"propagate-gravity-{sign}-azimuth",
                       f"(affects ?l1 ?l2)\n      ({flag} ?l1)\n      {_feels('?l1')}", sign, rate1)
    rest = ""
    if sign == "decrease":
        below = fmt_number(180 - options.hysteresis)
        start_range = f"(> (angle ?l {g}) {m})\n      (< (angle ?l {g}) {below})"
        stop_range = f"(<= (angle ?l {g}) 0)"
        # At rest the angle is set to exactly 0 (its value at the event's root): links that
        # came to rest apart must carry on with equal angles, or VAL sees their wraps a
        # rounding error apart and reports one "does not falsify its precondition".
        rest = f"\n      (assign (angle ?l {g}) 0)"
    else:
        # The upper end needs no test: at 360 back-to-zero wraps the angle to exactly 0.
        start_range = f"(> (angle ?l {g}) {fmt_number(180 + options.hysteresis)})"
        stop_range = f"(<= (angle ?l {g}) 180)"
    return f"""
  ;; DEPARTURE (VAL): events with Boolean flags record which way gravity would turn ?l
  ;; (self-falsifying under VAL's slack; start and stop thresholds {m} deg apart, so they
  ;; never bounce). They read only ?l's angle: no action triggers them, and no process reads
  ;; a changing angle, so every process starts and stops at a happening (benchmarks/results/
  ;; semantics.md: what VAL does otherwise). L1 (index 1) is clamped: never flagged.
  (:event start-gravity-{sign}
    :parameters (?l - link)
    :precondition (and
      (not ({flag} ?l))
      (not ({other} ?l))
      (> (link-index ?l) 1.5)
      {start_range})
    :effect (and
      ({flag} ?l){reset}))

  ;; Rest reached{" (or the vertical passed)" if sign == "increase" else ""}.
  (:event stop-gravity-{sign}
    :parameters (?l - link)
    :precondition (and
      ({flag} ?l)
      {stop_range})
    :effect (and
      (not ({flag} ?l)){rest}{reset}))
{_pass_vertical(g, reset) if sign == "decrease" else ""}
  ;; Gravity turns ?l toward rest (0 == 360); exactly 180 stays.
  (:process gravity-{sign}
    :parameters (?l - link)
    :precondition (and
      ({flag} ?l)
      {_feels("?l")})
    :effect (and ({sign} (angle ?l {g}) (* #t {rate}))))

  (:process propagate-gravity-{sign}
    :parameters (?l1 - link ?l2 - link)
    :precondition (and
      (affects ?l1 ?l2)
      ({flag} ?l1)
      {_feels("?l1")})
    :effect (and ({sign} (angle ?l2 {g}) (* #t {_carried(options, rate1, g)}))))
{azimuth}"""


def _pass_vertical(g: str, reset: str) -> str:
    """The event that ends a decreasing link's fall when it is carried up past the vertical
    (180): apart from the rest at 0, which sets the angle."""
    return f"""
  ;; The vertical passed, carried: gravity now turns ?l the other way.
  (:event pass-gravity-decrease
    :parameters (?l - link)
    :precondition (and
      (decreasing-angle-gravity ?l)
      (>= (angle ?l {g}) 180))
    :effect (and
      (not (decreasing-angle-gravity ?l)){reset}))
"""


_ACCELERATE = f"""
  ;; The speed of a falling link grows at the problem's (acceleration) [deg/s^2].
  (:process gravity-accelerate
    :parameters (?l - link)
    :precondition (and
      (or (decreasing-angle-gravity ?l) (increasing-angle-gravity ?l))
      {_feels("?l")})
    :effect (and (increase (gravity-speed ?l) (* #t (acceleration)))))
"""


def _reach() -> str:
    return """
  ;; After a release the hands need (reach-time) seconds before the next grasp.
  (:process reach
    :parameters ()
    :precondition (reaching)
    :effect (and (increase (reach-clock) (* #t 1))))

  (:event hands-ready
    :parameters ()
    :precondition (and
      (reaching)
      (>= (reach-clock) (reach-time)))
    :effect (and (not (reaching))))
"""


def _turned_event(name: str, degrees: float, what: str) -> str:
    """The event ``name``: a turn in progress has gone ``degrees`` [deg], far enough to
    unlock ``what``."""
    return f"""
  ;; A turn has gone far enough to unlock {what}.
  (:event {name}
    :parameters ()
    :precondition (and
      (in-use)
      (not ({name}))
      (>= (turned) {fmt_number(degrees)}))
    :effect (and ({name})))
"""


_TURNED = (_turned_event("turned-enough", CLEAR_DEG, "what the robot refused (CLEAR_DEG)")
           + _turned_event("turned-far", CLEAR_FAR_DEG,
                           "a link no hand could grasp (CLEAR_FAR_DEG)"))


def _observe(options: EncodingOptions) -> str:
    within = ("" if options.max_turn_deg is None
              else f"(<= (turned) {fmt_number(options.max_turn_deg)})")
    return f"""
  ;; No effect: lets a plan end at the moment a process completes the goal (VAL checks the
  ;; goal at the last happening).
  (:action observe
    :parameters ()
    :precondition (and{" " + within if within else ""})
    :effect (and))
"""


def domain_pddl(obj: ArticulatedObject | None, options: EncodingOptions) -> str:
    """The PDDL+ domain text for ``options``.

    Args:
        obj: The object (accepted for the interface; the domain is the same for every object:
            links, their number and their facts enter through the problem).
        options: Gravity model, planes and the gravity plane.

    Returns:
        The domain as PDDL+ text, ending with a newline.
    """
    del obj  # the domain does not depend on the object
    parts = [_header(options), _robot(options, "increase"), _robot(options, "decrease")]
    parts.append(_wrap_events(options))
    if options.has_gravity:
        parts += [_gravity(options, "decrease"), _gravity(options, "increase")]
    if options.model == "uacm":
        parts.append(_ACCELERATE)
    if options.has_reach:
        parts.append(_reach())
    if options.refusals:
        parts.append(_TURNED)
    parts.append(_observe(options))
    return "".join(parts) + ")\n"
