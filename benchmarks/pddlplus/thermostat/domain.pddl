(define (domain thermostat)
  (:requirements :typing :fluents :time :negative-preconditions)
  (:types room)
  (:predicates (heating ?r - room) (on-shift) (shift-done) (in-building ?r - room))
  (:functions (temp ?r - room) (heat-rate ?r - room) (loss-rate ?r - room)
              (t-low ?r - room) (t-high ?r - room) (t-goal ?r - room)
              (clock) (horizon) (power-used) (max-power))
  ;; ENHSP global constraint: every room stays in its band over the whole trajectory
  (:constraint comfort
    :parameters (?r - room)
    :condition (and (>= (temp ?r) (t-low ?r)) (<= (temp ?r) (t-high ?r))))
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
    :precondition (and (on-shift) (>= (clock) (horizon)))
    :effect (and (not (on-shift)) (shift-done)))
)
