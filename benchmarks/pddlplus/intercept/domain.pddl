(define (domain intercept)
  (:requirements :typing :fluents :time :negative-preconditions)
  (:types heading turn)
  (:predicates (hunting) (thrusting) (pending ?w - turn) (captured) (escaped))
  (:functions (px) (py) (pvx) (pvy) (tx) (ty) (tvx) (tvy) (clock) (speed) (fuel) (burn)
              (radius) (escape-time) (dx ?h - heading) (dy ?h - heading)
              (turn-time ?w - turn) (turn-vx ?w - turn) (turn-vy ?w - turn))
  (:process motion
    :parameters ()
    :precondition (and (hunting))
    :effect (and (increase (px) (* #t (pvx))) (increase (py) (* #t (pvy)))
                 (increase (tx) (* #t (tvx))) (increase (ty) (* #t (tvy)))
                 (increase (clock) (* #t 1))))
  (:process burning
    :parameters ()
    :precondition (and (hunting) (thrusting))
    :effect (and (decrease (fuel) (* #t (burn)))))
  (:event target-turns
    :parameters (?w - turn)
    :precondition (and (hunting) (pending ?w) (>= (clock) (turn-time ?w)))
    :effect (and (not (pending ?w)) (assign (tvx) (turn-vx ?w)) (assign (tvy) (turn-vy ?w))))
  (:event target-escapes
    :parameters ()
    :precondition (and (hunting) (not (escaped)) (>= (clock) (escape-time)))
    :effect (and (escaped)))
  (:event out-of-fuel
    :parameters ()
    :precondition (and (thrusting) (<= (fuel) 0))
    :effect (and (not (thrusting)) (assign (pvx) 0) (assign (pvy) 0)))
  (:action steer
    :parameters (?h - heading)
    :precondition (and (hunting) (> (fuel) 0))
    :effect (and (thrusting) (assign (pvx) (* (speed) (dx ?h))) (assign (pvy) (* (speed) (dy ?h)))))
  (:action halt
    :parameters ()
    :precondition (and (thrusting))
    :effect (and (not (thrusting)) (assign (pvx) 0) (assign (pvy) 0)))
  (:action capture
    :parameters ()
    :precondition (and (hunting) (not (escaped))
                       (<= (+ (* (- (px) (tx)) (- (px) (tx))) (* (- (py) (ty)) (- (py) (ty))))
                           (* (radius) (radius))))
    :effect (and (captured) (not (hunting))))
)
