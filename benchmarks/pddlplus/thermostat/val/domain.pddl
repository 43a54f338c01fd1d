(define (domain thermostat-val)
  (:requirements :typing :fluents :time :negative-preconditions)
  (:types room)
  (:predicates (heating ?r - room) (on-shift) (shift-done) (in-building ?r - room) (uncomfortable))
  (:functions (temp ?r - room) (heat-rate ?r - room) (loss-rate ?r - room)
              (t-low ?r - room) (t-high ?r - room) (t-goal ?r - room)
              (clock) (horizon) (power-used) (max-power))
  ;; VAL twin of the global constraint: leaving a band makes the shift a failure
  (:event too-cold
    :parameters (?r - room)
    :precondition (and (on-shift) (not (uncomfortable)) (< (temp ?r) (t-low ?r)))
    :effect (and (uncomfortable)))
  (:event too-hot
    :parameters (?r - room)
    :precondition (and (on-shift) (not (uncomfortable)) (> (temp ?r) (t-high ?r)))
    :effect (and (uncomfortable)))
  ;; (in-building ?r) is static; it is here because stock VAL's Validate crashes (SIGSEGV) on
  ;; a process whose precondition does not mention its parameter
  (:process cooling
    :parameters (?r - room)
    :precondition (and (on-shift) (in-building ?r))
    :effect (and (decrease (temp ?r) (* #t (loss-rate ?r)))))
  (:process heat
    :parameters (?r - room)
    :precondition (and (on-shift) (heating ?r))
    :effect (and (increase (temp ?r) (* #t (heat-rate ?r)))))
  (:process shift-clock
    :parameters ()
    :precondition (and (on-shift))
    :effect (and (increase (clock) (* #t 1))))
  (:action heater-on
    :parameters (?r - room)
    :precondition (and (on-shift) (not (heating ?r)) (< (power-used) (max-power)))
    :effect (and (heating ?r) (increase (power-used) 1)))
  (:action heater-off
    :parameters (?r - room)
    :precondition (and (heating ?r))
    :effect (and (not (heating ?r)) (decrease (power-used) 1)))
  (:action end-shift
    :parameters ()
    :precondition (and (on-shift) (>= (clock) (horizon)) (not (uncomfortable)))
    :effect (and (not (on-shift)) (shift-done)))
)
