(define (domain car-drag)
  (:requirements :typing :fluents :time)
  (:predicates (running) (stopped) (engine-blown))
  (:functions (d) (v) (a) (clock) (max-a) (min-a) (v-max) (d-min) (d-max) (v-tol) (deadline) (drag))
  ;; the car moves while the engine runs: v' = a, d' = v; the clock runs with it
  (:process moving
    :parameters ()
    :precondition (and (running))
    :effect (and (increase (v) (* #t (a)))
                 (increase (d) (* #t (v)))
                 (increase (clock) (* #t 1))))
  ;; quadratic air drag while moving forward: v' -= drag * v^2
  (:process air-drag
    :parameters ()
    :precondition (and (running) (> (v) 0))
    :effect (and (decrease (v) (* #t (* (^ (v) 2) (drag))))))
  (:event engine-explodes
    :parameters ()
    :precondition (and (running) (> (v) (v-max)))
    :effect (and (not (running)) (engine-blown)))
  (:action accelerate
    :parameters ()
    :precondition (and (running) (< (a) (max-a)))
    :effect (and (increase (a) 1)))
  (:action decelerate
    :parameters ()
    :precondition (and (running) (> (a) (min-a)))
    :effect (and (decrease (a) 1)))
  (:action stop
    :parameters ()
    :precondition (and (running)
                       (>= (d) (d-min)) (<= (d) (d-max))
                       (<= (v) (v-tol)) (>= (+ (v) (v-tol)) 0)
                       (<= (clock) (deadline)))
    :effect (and (not (running)) (stopped)))
)
