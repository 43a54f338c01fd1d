"""The PDDL+ grammar artiplan reads, as data: the parser walks these tables.

In BNF (PDDL 2.1 levels 2-4 plus PDDL+ processes and events, and ENHSP's global constraints
as an extension; durative actions are compiled into PDDL+ by :mod:`artiplan.pddl.durative`)::

    domain     ::= (define (domain NAME) SECTION*)
    SECTION    ::= (:requirements KEY*) | (:types TYPED*) | (:constants TYPED*)
                 | (:predicates (NAME TYPEDVAR*)*) | (:functions (NAME TYPEDVAR*) [- number]*)
                 | (:action|:process|:event NAME OPFIELD*) | (:durative-action NAME DAFIELD*)
                 | (:constraint NAME :parameters (TYPEDVAR*) :condition GD)   ; ENHSP
    OPFIELD    ::= :parameters (TYPEDVAR*) | :precondition GD | :effect EFFECT
    DAFIELD    ::= :parameters (TYPEDVAR*) | :duration GD | :condition GD | :effect EFFECT
    TYPED      ::= NAME+ [- TYPE] ...      TYPE ::= NAME | (either NAME+)
    GD         ::= () | ATOM | (not GD) | (and GD*) | (or GD*) | (imply GD GD)
                 | (exists (TYPEDVAR*) GD) | (forall (TYPEDVAR*) GD) | (COMP NEXP NEXP)
                 | (= TERM TERM) | (at start GD) | (at end GD) | (over all GD)
    NEXP       ::= NUMBER | (F TERM*) | F | (+ NEXP NEXP+) | (* NEXP NEXP+) | (- NEXP NEXP)
                 | (/ NEXP NEXP) | (^ NEXP NEXP) | (- NEXP) | #t | ?duration | total-time
    EFFECT     ::= () | ATOM | (not ATOM) | (and EFFECT*) | (forall (TYPEDVAR*) EFFECT)
                 | (when GD EFFECT) | (ASSIGNOP (F TERM*) NEXP) | (at start|at end EFFECT)
    problem    ::= (define (problem NAME) (:domain NAME) PSECTION*)
    PSECTION   ::= (:requirements KEY*) | (:objects TYPED*) | (:init INIT*) | (:goal GD)
                 | (:metric minimize|maximize NEXP)
    INIT       ::= ATOM | (= (F NAME*) NUMBER)
"""

from __future__ import annotations

#: Sections of a domain, each at most once except operators.
DOMAIN_SECTIONS = (
    ":requirements",
    ":types",
    ":constants",
    ":predicates",
    ":functions",
    ":action",
    ":process",
    ":event",
    ":durative-action",
    ":constraint",
)

#: Sections of a problem.
PROBLEM_SECTIONS = (":domain", ":requirements", ":objects", ":init", ":goal", ":metric")

#: Section keyword -> operator kind.
OPERATOR_SECTIONS = {
    ":action": "action",
    ":process": "process",
    ":event": "event",
    ":durative-action": "durative-action",
    ":constraint": "constraint",
}

#: The fields each operator kind accepts (any order; each at most once).
OPERATOR_FIELDS = {
    "action": (":parameters", ":precondition", ":effect"),
    "process": (":parameters", ":precondition", ":effect"),
    "event": (":parameters", ":precondition", ":effect"),
    "durative-action": (":parameters", ":duration", ":condition", ":effect"),
    "constraint": (":parameters", ":condition"),
}

#: Goal-description connectives with their arity: (minimum, maximum or None for unbounded).
CONNECTIVES = {
    "and": (0, None),
    "or": (0, None),
    "not": (1, 1),
    "imply": (2, 2),
}

QUANTIFIERS = ("exists", "forall")

COMPARISONS = ("<", "<=", ">", ">=", "=")

#: Arithmetic operators and their arity (minimum, maximum or None); ``-`` with one is unary.
ARITHMETIC = {"+": (2, None), "*": (2, None), "-": (1, 2), "/": (2, 2), "^": (2, 2)}

ASSIGN_OPS = ("assign", "increase", "decrease", "scale-up", "scale-down")

#: Timed specifiers of durative actions: first token -> (second token, name).
TIME_SPECIFIERS = {"at": {"start": "at start", "end": "at end"}, "over": {"all": "over all"}}

#: Special numeric symbols.
TIME_SYMBOL = "#t"
DURATION_SYMBOL = "?duration"
TOTAL_TIME = "total-time"

METRIC_DIRECTIONS = ("minimize", "maximize")

#: Requirements artiplan knows; others draw a warning. Value: the constructs each one allows,
#: used to warn about requirements a file declares but does not use.
REQUIREMENTS = {
    ":strips": (),
    ":typing": ("types",),
    ":negative-preconditions": ("negative",),
    ":disjunctive-preconditions": ("or", "imply"),
    ":equality": ("equality",),
    ":existential-preconditions": ("exists",),
    ":universal-preconditions": ("forall",),
    ":quantified-preconditions": ("exists", "forall"),
    ":conditional-effects": ("when", "forall-effect"),
    ":adl": (),
    ":fluents": ("functions",),
    ":numeric-fluents": ("functions",),
    ":object-fluents": (),
    ":durative-actions": ("durative-action",),
    ":duration-inequalities": ("durative-action",),
    ":continuous-effects": ("continuous",),
    ":time": ("process", "event", "continuous"),
    ":processes": ("process",),
    ":events": ("event",),
    ":timed-initial-literals": (),
    ":action-costs": ("functions",),
    ":preferences": (),
    ":constraints": (),
}

#: Requirements that imply others (checked for "unused" warnings as a group).
UMBRELLA_REQUIREMENTS = (":adl", ":strips", ":object-fluents", ":timed-initial-literals")

#: The root of the type hierarchy and the return type of numeric functions.
ROOT_TYPE = "object"
NUMBER_TYPE = "number"
