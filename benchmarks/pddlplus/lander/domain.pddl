(define (domain lander)
  (:requirements :typing :fluents :time :negative-preconditions)
  (:predicates (flying) (engine-on) (landed) (crashed))
  (:functions (h) (v) (mass) (fuel) (gravity) (thrust) (burn-rate) (touch-height) (safe-speed))
  (:process falling
    :parameters ()
    :precondition (and (flying))
    :effect (and (increase (h) (* #t (v))) (decrease (v) (* #t (gravity)))))
  ;; the rocket equation: the same thrust accelerates a lighter lander more
  (:process thrusting
    :parameters ()
    :precondition (and (flying) (engine-on))
    :effect (and (increase (v) (* #t (/ (thrust) (mass))))
                 (decrease (mass) (* #t (burn-rate)))
                 (decrease (fuel) (* #t (burn-rate)))))
  (:event fuel-exhausted
    :parameters ()
    :precondition (and (engine-on) (<= (fuel) 0))
    :effect (and (not (engine-on))))
  (:event crash
    :parameters ()
    :precondition (and (flying) (<= (h) 0))
    :effect (and (not (flying)) (crashed)))
  (:action ignite
    :parameters ()
    :precondition (and (flying) (not (engine-on)) (> (fuel) 0))
    :effect (and (engine-on)))
  (:action cut-off
    :parameters ()
    :precondition (and (engine-on))
    :effect (and (not (engine-on))))
  (:action touch-down
    :parameters ()
    :precondition (and (flying) (<= (h) (touch-height))
                       (>= (+ (v) (safe-speed)) 0) (<= (v) (safe-speed)))
    :effect (and (landed) (not (flying)) (not (engine-on))))
)
